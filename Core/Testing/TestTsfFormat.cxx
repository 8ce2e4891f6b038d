// MRtrix track scalar files (TsfFormat.h) and the radii of .tck files through "<name>.radius.tsf"
// (FiberFile.h): the Python-made sample checked byte by byte, every datatype, bad files with byte
// offsets / header lines, and the .tck + .tsf pair through readFiberFile / writeFiberFile.
#include "IO/FiberFile.h"
#include "IO/TckFormat.h"
#include "IO/TsfFormat.h"

#include "HandEncoding.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <vector>

#include <unistd.h>

using namespace fiberpli;
using fiberpli::testing::encode;

namespace
{

const double NaN = std::numeric_limits<double>::quiet_NaN();
const double Inf = std::numeric_limits<double>::infinity();

std::string slurp(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void spit(const std::string& path, const std::string& bytes)
{
  std::ofstream(path, std::ios::binary) << bytes;
}

TsfReadResult readBytes(const std::string& bytes)
{
  std::istringstream in(bytes);
  return readTsf(in, "r.tsf");
}

/// A .tsf with the given header keys and body; the `file:` offset is the header's own length.
std::string tsfFile(const std::string& keys, const std::string& body,
  const std::string& magic = "mrtrix track scalars")
{
  std::size_t offset = 0;
  for (;;)
  {
    const std::string h = magic + "\n" + keys + "file: . " + std::to_string(offset) + "\nEND\n";
    if (h.size() == offset)
    {
      return h + body;
    }
    offset = h.size();
  }
}

struct TempDir
{
  std::string path;
  TempDir()
  {
    char tmpl[] = "/tmp/fiberpli-tsf-XXXXXX";
    path = ::mkdtemp(tmpl);
  }
  ~TempDir()
  {
    for (const char* f : { "x.tck", "x.radius.tsf" })
    {
      ::unlink((path + "/" + f).c_str());
    }
    ::rmdir(path.c_str());
  }
};

/// Two fibers of 3 and 2 points with radii that float32 cannot hold exactly (0.1, 1/3).
FiberModel pairModel()
{
  FiberModel m;
  Fiber a;
  a.points = { { 0, 0, 0 }, { 1, 0, 0 }, { 2, 0.5, 0 } };
  a.radii = { 0.1, 1.0 / 3.0, 2.5 };
  Fiber b;
  b.points = { { 0, 1, 0 }, { 0, 2, 1 } };
  b.radii = { 7.0, 1e-3 };
  b.bundle = 1;
  m.fibers = { a, b };
  return m;
}

} // namespace

TEST(TsfFormat, WriterMatchesThePythonSampleByteByByte)
{
  // Testing/Data/tracks/sample.radius.tsf was written with Python's struct module (README there).
  const std::string path = std::string(FIBERPLI_TEST_DATA_DIR) + "/tracks/sample.radius.tsf";
  const std::string sample = slurp(path);
  const std::string header = "mrtrix track scalars\ndatatype: Float32LE\ntimestamp: "
                             "657864492963474\ncount: 2\nfile: . 92\nEND\n";
  ASSERT_EQ(header.size(), 92u);
  const unsigned char data[] = {
    0x00, 0x00, 0x00, 0x3f, 0x00, 0x00, 0xa0, 0x3f, 0x00, 0x00, 0xc0, 0x7f, // 0.5 1.25 NaN
    0x00, 0x00, 0x00, 0x40, 0xcd, 0xcc, 0xcc, 0x3d, 0x00, 0x00, 0xc0, 0x7f, // 2 0.1f NaN
    0x00, 0x00, 0x80, 0x7f,                                                 // Inf
  };
  const std::string expected =
    header + std::string(reinterpret_cast<const char*>(data), sizeof data);
  ASSERT_EQ(sample, expected) << "the committed sample is not what the README describes";

  std::ostringstream out;
  ASSERT_EQ(writeTsf(out, { { 0.5, 1.25 }, { 2, 0.1 } }, "657864492963474"), "");
  const std::string got = out.str();
  ASSERT_EQ(got.size(), expected.size());
  for (std::size_t i = 0; i < got.size(); ++i)
  {
    ASSERT_EQ(static_cast<unsigned char>(got[i]), static_cast<unsigned char>(expected[i]))
      << "byte " << i;
  }

  const TsfReadResult r = readBytes(sample);
  ASSERT_TRUE(r.ok()) << r.error;
  EXPECT_EQ(r.timestamp, "657864492963474");
  ASSERT_EQ(r.values.size(), 2u);
  EXPECT_EQ(r.values[0], (std::vector<double>{ 0.5, 1.25 }));
  EXPECT_EQ(r.values[1], (std::vector<double>{ 2.0, static_cast<double>(0.1f) }));
  EXPECT_EQ(r.firstValueOffsets, (std::vector<std::uint64_t>{ 92, 104 }));
  EXPECT_EQ(r.byteOffset(1, 1), 108u); // where 0xcd 0xcc 0xcc 0x3d sits

  // No timestamp line when none is given.
  std::ostringstream bare;
  ASSERT_EQ(writeTsf(bare, {}, ""), "");
  EXPECT_EQ(bare.str().substr(0, bare.str().size() - 4),
    "mrtrix track scalars\ndatatype: Float32LE\ncount: 0\nfile: . 65\nEND\n"); // 21 + 20 + 9 + 11 +
                                                                               // 4
}

TEST(TsfFormat, ReadsEveryDatatypeEmptyStreamlinesAndNoCount)
{
  for (const char* type : { "Float32LE", "Float32BE", "Float64LE", "Float64BE" })
  {
    const bool f64 = type[5] == '6';
    const bool be = type[7] == 'B';
    const std::vector<double> body = { 1.5, -2, 3, NaN, NaN, 1e-3, NaN, Inf };
    for (const std::string count : { "count: 3\n", "" })
    {
      const std::string file =
        tsfFile("datatype: " + std::string(type) + "\ntimestamp: 17.5\nroi: x\n" + count,
          encode(body, f64, be));
      const TsfReadResult r = readBytes(file);
      ASSERT_TRUE(r.ok()) << type << ": " << r.error;
      EXPECT_EQ(r.timestamp, "17.5");
      ASSERT_EQ(r.values.size(), 3u) << type;
      EXPECT_EQ(r.values[0], (std::vector<double>{ 1.5, -2, 3 })) << type;
      EXPECT_TRUE(r.values[1].empty());
      EXPECT_EQ(r.values[2][0], f64 ? 1e-3 : static_cast<double>(1e-3f)) << type;
      const std::size_t vs = f64 ? 8 : 4;
      const std::size_t start = file.size() - body.size() * vs;
      EXPECT_EQ(r.valueSize, vs);
      EXPECT_EQ(
        r.firstValueOffsets, (std::vector<std::uint64_t>{ start, start + 4 * vs, start + 5 * vs }))
        << type;
    }
  }
}

TEST(TsfFormat, BadFilesNameTheProblemAndWhere)
{
  const std::string data = encode({ 1, 2, NaN, 3, 4, NaN, Inf }, false, false);
  const std::string good = tsfFile("datatype: Float32LE\ncount: 2\n", data);
  ASSERT_TRUE(readBytes(good).ok()) << readBytes(good).error;
  const std::size_t dataStart = good.size() - data.size();
  struct Case
  {
    std::string bytes;
    std::string expect;
  };
  const std::vector<Case> cases = {
    { tsfFile("datatype: Float32LE\n", data, "mrtrix tracks"),
      "r.tsf line 1: not an MRtrix track scalars file (first line must be 'mrtrix track "
      "scalars')" },
    { tsfFile("datatype: Int32LE\n", data), "r.tsf line 2: datatype 'Int32LE' is not supported" },
    { "mrtrix track scalars\ndatatype: Float32LE\nEND\n",
      "r.tsf: header has no 'file: . <offset>' line" },
    { "mrtrix track scalars\ndatatype: Float32LE\nfile: . 3\nEND\n",
      "r.tsf line 3: data offset 3 must lie between" },
    { "mrtrix track scalars\ndatatype: Float32LE\nfile: . 60\n",
      "header ends without an END line" },
    { tsfFile("datatype: Float32LE\ntimestamp: 1\ntimestamp: 2\n", data),
      "r.tsf line 4: 'timestamp' given twice" },
    { tsfFile("datatype: Float32LE\ncount: 3\n", data),
      "r.tsf line 3: header count 3 but the data holds 2 streamlines" },
    { tsfFile("datatype: Float32LE\ncount: 1\n", data),
      "header count 1 but the data holds 2 streamlines" },
    { tsfFile("datatype: Float32LE\ncount: 5000000000\n", data),
      "count 5000000000 needs at least 5000000001 values but only 28 bytes" },
    { tsfFile("datatype: Float32LE\ncount: 2\n", data.substr(0, data.size() - 4)),
      "r.tsf byte " + std::to_string(dataStart + data.size() - 4) +
        ": data ends without the Inf end-of-tracks value" },
    { tsfFile("datatype: Float32LE\ncount: 2\n", data.substr(0, data.size() - 2)),
      "data ends without the Inf" },
  };
  for (const Case& c : cases)
  {
    const TsfReadResult r = readBytes(c.bytes);
    EXPECT_FALSE(r.ok()) << c.expect;
    EXPECT_NE(r.error.find(c.expect), std::string::npos)
      << "got: " << r.error << "\nwanted: " << c.expect;
    EXPECT_TRUE(r.values.empty());
  }
}

TEST(TsfFormat, WriterRefusesValuesThatWouldBreakTheStructure)
{
  std::ostringstream out;
  EXPECT_NE(writeTsf(out, { { 1, 2 }, { 3, NaN } }, "").find("streamline 1 point 1 has value nan"),
    std::string::npos);
  EXPECT_NE(writeTsf(out, { { Inf } }, "").find("streamline 0 point 0"), std::string::npos);
  EXPECT_NE(writeTsf(out, { { 1e39 } }, "").find("float32 range"), std::string::npos);
  EXPECT_NE(writeTsf(out, { { 1 } }, "1\nEND").find("line break"), std::string::npos);
  EXPECT_TRUE(out.str().empty()) << "nothing is written on refusal";
}

TEST(TckRadii, RadiusPathReplacesTheExtension)
{
  EXPECT_EQ(tckRadiusPath("/d/x.tck"), "/d/x.radius.tsf");
  EXPECT_EQ(tckRadiusPath("/d.e/x.TCK"), "/d.e/x.radius.tsf");
  EXPECT_EQ(tckRadiusPath("/d.e/x"), "/d.e/x.radius.tsf");
}

TEST(TckRadii, CommittedSamplePairGivesTheTsfRadii)
{
  const std::string path = std::string(FIBERPLI_TEST_DATA_DIR) + "/tracks/sample.tck";
  const FiberReadResult r = readFiberFile(path, 9.0);
  ASSERT_TRUE(r.ok()) << r.error;
  ASSERT_EQ(r.model.fibers.size(), 2u);
  EXPECT_EQ(r.model.fibers[0].radii, (std::vector<double>{ 0.5, 1.25 }));
  EXPECT_EQ(r.model.fibers[1].radii, (std::vector<double>{ 2.0, static_cast<double>(0.1f) }));
}

TEST(TckRadii, RoundTripKeepsRadiiToFloatPrecisionAndTimestampsMatch)
{
  TempDir dir;
  const std::string tck = dir.path + "/x.tck";
  const FiberModel m = pairModel();
  ASSERT_EQ(writeFiberFile(tck, m), "");
  const FiberReadResult r = readFiberFile(tck, 100.0);
  ASSERT_TRUE(r.ok()) << r.error;
  ASSERT_EQ(r.model.fibers.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k)
  {
    ASSERT_EQ(r.model.fibers[k].radii.size(), m.fibers[k].radii.size());
    for (std::size_t i = 0; i < m.fibers[k].radii.size(); ++i)
    {
      EXPECT_EQ(
        r.model.fibers[k].radii[i], static_cast<double>(static_cast<float>(m.fibers[k].radii[i])))
        << "fiber " << k << " point " << i;
    }
  }
  EXPECT_NE(r.model.fibers[0].radii[0], 0.1) << "float32 rounding is expected, not exactness";

  // Both headers carry the same timestamp, and writing is deterministic.
  std::istringstream tckIn(slurp(tck));
  std::string tckStamp;
  ASSERT_TRUE(readTck(tckIn, "x.tck", 1.0, &tckStamp).ok());
  std::istringstream tsfIn(slurp(tckRadiusPath(tck)));
  const TsfReadResult tsf = readTsf(tsfIn, "x.radius.tsf");
  ASSERT_TRUE(tsf.ok()) << tsf.error;
  EXPECT_EQ(tsf.timestamp, tckStamp);
  EXPECT_EQ(tckStamp, tckTimestamp(m));
  const std::string first = slurp(tck) + slurp(tckRadiusPath(tck));
  ASSERT_EQ(writeFiberFile(tck, r.model), "");
  EXPECT_EQ(slurp(tck) + slurp(tckRadiusPath(tck)), first)
    << "rewriting what was read gives the same bytes";
}

TEST(TckRadii, MissingTsfGivesDefaultRadius)
{
  TempDir dir;
  const std::string tck = dir.path + "/x.tck";
  ASSERT_EQ(writeFiberFile(tck, pairModel()), "");
  ASSERT_EQ(::unlink(tckRadiusPath(tck).c_str()), 0);
  const FiberReadResult r = readFiberFile(tck, 0.75);
  ASSERT_TRUE(r.ok()) << r.error;
  EXPECT_EQ(r.model.fibers[0].radii, (std::vector<double>{ 0.75, 0.75, 0.75 }));
  EXPECT_EQ(r.model.fibers[1].radii, (std::vector<double>{ 0.75, 0.75 }));
}

TEST(TckRadii, MismatchedOrBadTsfIsAnErrorNamingIt)
{
  TempDir dir;
  const std::string tck = dir.path + "/x.tck";
  const std::string tsf = tckRadiusPath(tck);
  const FiberModel m = pairModel();
  ASSERT_EQ(writeFiberFile(tck, m), "");
  const std::string stamp = tckTimestamp(m);
  auto tsfWith = [&](const std::vector<std::vector<double>>& values, const std::string& ts)
  {
    std::ostringstream out;
    EXPECT_EQ(writeTsf(out, values, ts), "");
    return out.str();
  };
  // Header length of a Float32LE .tsf with this timestamp and count 2, hence where data starts.
  const std::size_t start = tsfWith({ { 1, 1, 1 }, { 1, 1 } }, stamp).size() - 4 * 8;
  struct Case
  {
    std::string bytes;
    std::string expect;
  };
  const std::vector<Case> cases = {
    { tsfWith({ { 1, 1, 1 }, { 1, 1 }, { 1, 1 } }, stamp),
      tsf + ": holds 3 streamlines but " + tck + " holds 2" },
    { tsfWith({ { 1, 1, 1 } }, stamp), tsf + ": holds 1 streamlines but " + tck + " holds 2" },
    { tsfWith({ { 1, 1 }, { 1, 1 } }, stamp),
      tsf + " byte " + std::to_string(start) + ": streamline 0 has 2 values but 3 points in " +
        tck },
    { tsfWith({ { 1, 1, 1 }, { 1, 1, 1 } }, stamp),
      tsf + " byte " + std::to_string(start + 16) + ": streamline 1 has 3 values but 2 points in " +
        tck },
    { tsfWith({ { 1, 1, 1 }, { 1, 1 } }, "12345"),
      tsf + ": timestamp '12345' differs from timestamp '" + stamp + "' of " + tck },
    { tsfWith({ { 1, 0, 1 }, { 1, 1 } }, stamp),
      tsf + " byte " + std::to_string(start + 4) +
        ": radius 0 of streamline 0 point 1 must be finite and > 0" },
    { tsfWith({ { 1, 1, 1 }, { 1, -0.5 } }, stamp),
      tsf + " byte " + std::to_string(start + 20) +
        ": radius -0.5 of streamline 1 point 1 must be finite and > 0" },
    // A NaN is the streamline separator, so a NaN radius splits the streamline: caught as a
    // mismatch.
    { tsfFile("datatype: Float32LE\ncount: 2\n",
        encode({ 1, NaN, 1, NaN, 1, 1, NaN, Inf }, false, false)),
      tsf + " line 3: header count 2 but the data holds 3 streamlines" },
    { tsfFile("datatype: Float32LE\n", encode({ 1, NaN, 1, NaN, 1, 1, NaN, Inf }, false, false)),
      tsf + ": holds 3 streamlines but " + tck + " holds 2" },
    { "mrtrix tracks\n", tsf + " line 1: not an MRtrix track scalars file" },
  };
  for (const Case& c : cases)
  {
    spit(tsf, c.bytes);
    const FiberReadResult r = readFiberFile(tck, 1.0);
    EXPECT_FALSE(r.ok()) << c.expect;
    EXPECT_NE(r.error.find(c.expect), std::string::npos)
      << "got: " << r.error << "\nwanted: " << c.expect;
    EXPECT_TRUE(r.model.fibers.empty());
  }
  // Without a timestamp in the .tsf (e.g. written by other tools) the structure check alone
  // decides.
  spit(tsf, tsfWith({ { 1, 2, 3 }, { 4, 5 } }, ""));
  const FiberReadResult ok = readFiberFile(tck, 1.0);
  ASSERT_TRUE(ok.ok()) << ok.error;
  EXPECT_EQ(ok.model.fibers[1].radii, (std::vector<double>{ 4, 5 }));
}

TEST(TckRadii, DroppedShortStreamlinesMustBeShortInTheTsfToo)
{
  TempDir dir;
  const std::string tck = dir.path + "/x.tck";
  const std::string tsf = tckRadiusPath(tck);
  // Streamlines of 2, 1 and 2 points: readTck drops the middle one but keeps its position (id 1).
  const std::string tckBody = encode({ 0, 0, 0, 1, 0, 0, NaN, NaN, NaN, 5, 5, 5, NaN, NaN, NaN, 0,
                                       1, 0, 0, 2, 0, NaN, NaN, NaN, Inf, Inf, Inf },
    false, false);
  spit(tck, tsfFile("datatype: Float32LE\ncount: 3\n", tckBody, "mrtrix tracks"));
  spit(tsf,
    tsfFile("datatype: Float32LE\ncount: 3\n",
      encode({ 1, 2, NaN, 9, NaN, 3, 4, NaN, Inf }, false, false)));
  const FiberReadResult r = readFiberFile(tck, 1.0);
  ASSERT_TRUE(r.ok()) << r.error;
  EXPECT_EQ(r.droppedFibers, 1u);
  ASSERT_EQ(r.model.fibers.size(), 2u);
  EXPECT_EQ(r.model.fibers[1].id, 2);
  EXPECT_EQ(r.model.fibers[1].radii, (std::vector<double>{ 3, 4 }));
  spit(tsf,
    tsfFile("datatype: Float32LE\ncount: 3\n",
      encode({ 1, 2, NaN, 9, 9, NaN, 3, 4, NaN, Inf }, false, false)));
  const FiberReadResult bad = readFiberFile(tck, 1.0);
  EXPECT_NE(bad.error.find("streamline 1 has 2 values but fewer than 2 points"), std::string::npos)
    << bad.error;
}

TEST(TckRadii, RadiiFloat32CannotHoldAreRefusedBeforeAnyFileIsTouched)
{
  TempDir dir;
  const std::string tck = dir.path + "/x.tck";
  ASSERT_EQ(writeFiberFile(tck, pairModel()), "");
  const std::string before = slurp(tck) + slurp(tckRadiusPath(tck));
  FiberModel m = pairModel();
  m.fibers[1].radii[0] = 1e-50; // float32 rounds it to 0
  const std::string err = writeFiberFile(tck, m);
  EXPECT_NE(err.find(tckRadiusPath(tck) +
              ": cannot write .tsf: fiber 1 (fiber_id 0) point 0 has radius 1e-50"),
    std::string::npos)
    << err;
  m.fibers[1].radii[0] = 1e39;
  EXPECT_NE(writeFiberFile(tck, m).find("has radius 1e+39"), std::string::npos);
  EXPECT_EQ(slurp(tck) + slurp(tckRadiusPath(tck)), before);
}
