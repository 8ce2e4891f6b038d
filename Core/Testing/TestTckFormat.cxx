// MRtrix .tck reader/writer (TckFormat.h, docs/api.md §4): a hand-made file checked
// byte by byte, every datatype, round trip, bad files with byte offsets / header lines, sniffing.
#include "IO/TckFormat.h"

#include "HandEncoding.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <vector>

using namespace fiberpli;
using fiberpli::testing::encode;

namespace
{

FiberReadResult readBytes(const std::string& bytes, double radius = 0.5)
{
  std::istringstream in(bytes);
  return readTck(in, "t.tck", radius);
}

const double NaN = std::numeric_limits<double>::quiet_NaN();
const double Inf = std::numeric_limits<double>::infinity();

/// Two streamlines (3 and 2 points) and an empty one, as MRtrix would lay them out.
std::vector<double> sampleValues()
{
  return { 1, 2, 3, 4, 5, 6, 7, 8, 9, NaN, NaN, NaN, -1, 0.5, 0.25, -2, 0, 1000, NaN, NaN, NaN, NaN,
    NaN, NaN, Inf, Inf, Inf };
}

std::string headerWithOffset(
  const std::string& datatype, const std::string& extra, std::size_t offset)
{
  return "mrtrix tracks\ndatatype: " + datatype + "\n" + extra + "file: . " +
    std::to_string(offset) + "\nEND\n";
}

} // namespace

TEST(TckFormat, HostIsLittleEndianForTheseHandEncodings)
{
  const std::uint32_t one = 1;
  unsigned char b[4];
  std::memcpy(b, &one, 4);
  ASSERT_EQ(b[0], 1);
}

TEST(TckFormat, WriterMatchesTheSpecByteByByte)
{
  FiberModel m;
  Fiber a;
  a.points = { { 1, 2, 3 }, { 4, 5, 6 } };
  a.radii = { 3, 3 }; // not stored in .tck
  Fiber b;
  b.points = { { 0.5, -1, -2 }, { 0.25, 0, 1 } };
  b.radii = { 1, 2 };
  b.bundle = 4; // not stored either
  m.fibers = { a, b };
  std::ostringstream out;
  ASSERT_EQ(writeTck(out, m), "");
  // Header: 14 + 20 + 27 + 9 + 11 + 4 = 85 bytes, so the data starts at byte 85. The timestamp is
  // FNV-1a 64 of the data bytes below modulo 10^15, computed with Python
  // (Testing/Data/tracks/README.md).
  const std::string header =
    "mrtrix tracks\ndatatype: Float32LE\ntimestamp: 657864492963474\ncount: 2\nfile: . 85\nEND\n";
  ASSERT_EQ(header.size(), 85u);
  EXPECT_EQ(tckTimestamp(m), "657864492963474");
  const unsigned char data[] = {
    0x00, 0x00, 0x80, 0x3f, 0x00, 0x00, 0x00, 0x40, 0x00, 0x00, 0x40, 0x40, // 1 2 3
    0x00, 0x00, 0x80, 0x40, 0x00, 0x00, 0xa0, 0x40, 0x00, 0x00, 0xc0, 0x40, // 4 5 6
    0x00, 0x00, 0xc0, 0x7f, 0x00, 0x00, 0xc0, 0x7f, 0x00, 0x00, 0xc0,
    0x7f, // NaN: end of streamline
    0x00, 0x00, 0x00, 0x3f, 0x00, 0x00, 0x80, 0xbf, 0x00, 0x00, 0x00, 0xc0, // 0.5 -1 -2
    0x00, 0x00, 0x80, 0x3e, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x80, 0x3f, // 0.25 0 1
    0x00, 0x00, 0xc0, 0x7f, 0x00, 0x00, 0xc0, 0x7f, 0x00, 0x00, 0xc0, 0x7f, // NaN
    0x00, 0x00, 0x80, 0x7f, 0x00, 0x00, 0x80, 0x7f, 0x00, 0x00, 0x80, 0x7f, // Inf: end of file
  };
  const std::string expected =
    header + std::string(reinterpret_cast<const char*>(data), sizeof data);
  const std::string got = out.str();
  ASSERT_EQ(got.size(), expected.size());
  for (std::size_t i = 0; i < got.size(); ++i)
  {
    ASSERT_EQ(static_cast<unsigned char>(got[i]), static_cast<unsigned char>(expected[i]))
      << "byte " << i;
  }

  // And the reader reads the hand-made bytes back.
  const FiberReadResult r = readBytes(expected, 0.75);
  ASSERT_TRUE(r.ok()) << r.error;
  ASSERT_EQ(r.model.fibers.size(), 2u);
  EXPECT_EQ(r.model.fibers[1].points[0], (Vec3{ 0.5, -1, -2 }));
  EXPECT_EQ(r.model.fibers[1].radii, (std::vector<double>{ 0.75, 0.75 }));
  EXPECT_EQ(r.model.fibers[1].bundle, 0);
  EXPECT_EQ(r.model.fibers[1].id, 1);
}

TEST(TckFormat, ReadsEveryDatatypeAndIgnoresOtherKeys)
{
  const char* types[] = { "Float32LE", "Float32BE", "Float64LE", "Float64BE" };
  for (const char* type : types)
  {
    const bool f64 = type[5] == '6';
    const bool be = type[7] == 'B';
    // Padding between header and data (as MRtrix's MATLAB writer leaves) and extra keys.
    const std::string extra =
      "timestamp: 1700000000.1\ncommand_history: tckgen a b\ncount: 3\ntotal_count: 3\n";
    const std::size_t offset = headerWithOffset(type, extra, 100).size() + 7;
    std::string file = headerWithOffset(type, extra, offset);
    file += std::string(offset - file.size(), '\0');
    file += encode(sampleValues(), f64, be);
    const FiberReadResult r = readBytes(file, 0.5);
    ASSERT_TRUE(r.ok()) << type << ": " << r.error;
    ASSERT_EQ(r.model.fibers.size(), 2u) << type;
    EXPECT_EQ(r.droppedFibers, 1u) << "the empty streamline";
    EXPECT_EQ(r.model.fibers[0].points.size(), 3u);
    EXPECT_EQ(r.model.fibers[0].points[2], (Vec3{ 7, 8, 9 })) << type;
    EXPECT_EQ(r.model.fibers[1].points[1], (Vec3{ -2, 0, 1000 })) << type;
    EXPECT_EQ(r.model.fibers[1].radii[0], 0.5);
  }
}

TEST(TckFormat, RoundTripKeepsPointsToFloatPrecision)
{
  FiberModel m;
  for (int k = 0; k < 5; ++k)
  {
    Fiber f;
    f.id = 10 + k;
    for (int i = 0; i <= k + 1; ++i)
    {
      f.points.push_back({ 0.1 * i + k, std::sqrt(2.0) * i, -3.7e4 * k });
      f.radii.push_back(1.0);
    }
    m.fibers.push_back(f);
  }
  std::ostringstream out;
  ASSERT_EQ(writeTck(out, m), "");
  const FiberReadResult r = readBytes(out.str(), 2.5);
  ASSERT_TRUE(r.ok()) << r.error;
  ASSERT_EQ(r.model.fibers.size(), m.fibers.size());
  for (std::size_t k = 0; k < m.fibers.size(); ++k)
  {
    ASSERT_EQ(r.model.fibers[k].points.size(), m.fibers[k].points.size());
    EXPECT_EQ(r.model.fibers[k].id, static_cast<std::int64_t>(k)); // ids are file positions
    for (std::size_t i = 0; i < m.fibers[k].points.size(); ++i)
    {
      for (int a = 0; a < 3; ++a)
      {
        EXPECT_EQ(r.model.fibers[k].points[i][a],
          static_cast<double>(static_cast<float>(m.fibers[k].points[i][a])));
      }
      EXPECT_EQ(r.model.fibers[k].radii[i], 2.5);
    }
  }
  // Writing what was read gives the same bytes again.
  std::ostringstream again;
  ASSERT_EQ(writeTck(again, r.model), "");
  EXPECT_EQ(again.str(), out.str());
}

TEST(TckFormat, BadFilesNameTheProblemAndWhere)
{
  const std::string data = encode(sampleValues(), false, false);
  auto file =
    [&](const std::string& extra, const std::string& body, const std::string& type = "Float32LE")
  {
    std::size_t offset = 0;
    while (
      headerWithOffset(type, extra, offset).size() != offset) // header length includes its digits
    {
      offset = headerWithOffset(type, extra, offset).size();
    }
    return headerWithOffset(type, extra, offset) + body;
  };
  struct Case
  {
    std::string bytes;
    std::string expect;
  };
  const std::string good = file("count: 3\n", data);
  ASSERT_TRUE(readBytes(good).ok()) << readBytes(good).error;
  const std::size_t dataStart = good.size() - data.size();
  const std::vector<Case> cases = {
    { "mrtrix image\ndatatype: Float32LE\n", "t.tck line 1: not an MRtrix tracks file" },
    { std::string("\x7f"
                  "ELF\0\0\0",
        7),
      "t.tck line 1:" },
    { file("count: 3\n", data, "Int16LE"), "datatype 'Int16LE' is not supported" },
    { "mrtrix tracks\ndatatype: Float32LE\ncount: 0\nEND\n", "no 'file: . <offset>' line" },
    { "mrtrix tracks\nfile: . 40\nEND\n", "no 'datatype' line" },
    { "mrtrix tracks\ndatatype: Float32LE\nfile: other.dat 0\nEND\n",
      "t.tck line 3: 'file: other.dat 0': only data in the same file" },
    { "mrtrix tracks\ndatatype: Float32LE\nfile: . abc\nEND\n",
      "t.tck line 3: 'file: . abc': offset is not a number" },
    { "mrtrix tracks\ndatatype: Float32LE\nfile: . 5\nEND\n", "data offset 5 must lie between" },
    { "mrtrix tracks\ndatatype: Float32LE\nfile: . 99999\nEND\n",
      "data offset 99999 must lie between" },
    { "mrtrix tracks\ndatatype: Float32LE\nfile: . 50\n", "header ends without an END line" },
    { "mrtrix tracks\ndatatype: Float32LE\nthis line has no colon\nEND\n",
      "t.tck line 3: header line is not 'key: value'" },
    { "mrtrix tracks\ndatatype: Float32LE\ndatatype: Float64LE\nEND\n",
      "t.tck line 3: 'datatype' given twice" },
    { file("count: 4000000000\n", data), "count 4000000000 needs at least 4000000001 triplets" },
    { file("count: 2\n", data), "header count 2 but the data holds 3 streamlines" },
    { file("count: 4\n", data), "header count 4 but the data holds 3 streamlines" },
    { file("count: -1\n", data), "count '-1' is not a number" },
    { file("count: 3\n", data.substr(0, data.size() - 12)),
      "data ends without the Inf end-of-tracks triplet" },
    { file("count: 3\n", data.substr(0, data.size() - 5)),
      "data ends without the Inf end-of-tracks triplet" },
    { file("count: 1\n", encode({ 1, 2, 3, NaN, 1, 2, Inf, Inf, Inf }, false, false)),
      "t.tck byte " + std::to_string(dataStart + 12) +
        ": triplet mixes finite and NaN/Inf values" },
  };
  for (const Case& c : cases)
  {
    const FiberReadResult r = readBytes(c.bytes);
    EXPECT_FALSE(r.ok()) << c.expect;
    EXPECT_NE(r.error.find(c.expect), std::string::npos)
      << "got: " << r.error << "\nwanted: " << c.expect;
    EXPECT_TRUE(r.model.fibers.empty());
  }
  EXPECT_NE(
    readBytes(good, 0.0).error.find("DefaultRadius 0 must be finite and > 0"), std::string::npos);
  EXPECT_NE(readBytes(good, NaN).error.find("DefaultRadius"), std::string::npos);
}

TEST(TckFormat, WriterRefusesWhatItCannotStore)
{
  FiberModel m;
  Fiber f;
  f.points = { { 0, 0, 0 }, { 1e39, 0, 0 } };
  f.radii = { 1, 1 };
  f.id = 77;
  m.fibers = { f };
  std::ostringstream out;
  const std::string err = writeTck(out, m);
  EXPECT_NE(err.find("fiber 0 (fiber_id 77) point 1"), std::string::npos) << err;
  EXPECT_NE(err.find("float32 range"), std::string::npos) << err;
  m.fibers[0].points.pop_back();
  m.fibers[0].radii.pop_back();
  EXPECT_NE(writeTck(out, m).find("fewer than 2 points"), std::string::npos);
}

TEST(TckFormat, Sniffing)
{
  auto sniff = [](const std::string& s)
  {
    std::istringstream in(s);
    const bool yes = looksLikeTck(in);
    EXPECT_EQ(in.tellg(), std::streampos(0));
    return yes;
  };
  EXPECT_TRUE(sniff("mrtrix tracks\ndatatype: Float32LE\n"));
  EXPECT_TRUE(sniff("mrtrix tracks\r\n"));
  EXPECT_FALSE(sniff("mrtrix image\n"));
  EXPECT_FALSE(sniff("mrtrix tracksX\n"));
  EXPECT_FALSE(sniff("1 2 3 0.5\n"));
  EXPECT_FALSE(sniff(""));
}

TEST(TckFormat, CommittedSampleEqualsWriterOutput)
{
  // Testing/Data/tracks/sample.tck was written with Python's struct module from the spec (the
  // same two streamlines as WriterMatchesTheSpecByteByByte).
  const std::string path = std::string(FIBERPLI_TEST_DATA_DIR) + "/tracks/sample.tck";
  std::ifstream in(path, std::ios::binary);
  ASSERT_TRUE(in) << path;
  EXPECT_TRUE(looksLikeTck(in));
  const FiberReadResult r = readTck(in, path, 1.0);
  ASSERT_TRUE(r.ok()) << r.error;
  ASSERT_EQ(r.model.fibers.size(), 2u);
  EXPECT_EQ(r.model.fibers[0].points[1], (Vec3{ 4, 5, 6 }));
  EXPECT_EQ(r.model.fibers[1].points[1], (Vec3{ 0.25, 0, 1 }));
  std::ostringstream out;
  ASSERT_EQ(writeTck(out, r.model), "");
  std::ifstream again(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << again.rdbuf();
  EXPECT_EQ(out.str(), bytes.str());
}
