// fastPLI .dat reader/writer (docs/api.md §4, DatFormat.h): layout, bit-exact round
// trip, the real fastPLI sample files, every bad-line case, content sniffing.
#include "IO/DatFormat.h"
#include "Util/Random.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

using namespace fiberpli;

namespace
{

FiberReadResult readString(const std::string& text)
{
  std::istringstream in(text);
  return readFastPliDat(in, "test.dat");
}

Fiber makeFiber(int bundle, std::initializer_list<std::array<double, 4>> pts)
{
  Fiber f;
  f.bundle = bundle;
  for (const auto& p : pts)
  {
    f.points.push_back({ p[0], p[1], p[2] });
    f.radii.push_back(p[3]);
  }
  return f;
}

bool sameBits(double a, double b)
{
  return std::memcmp(&a, &b, sizeof a) == 0;
}

std::string dataPath(const std::string& name)
{
  return std::string(FIBERPLI_TEST_DATA_DIR) + "/" + name;
}

} // namespace

TEST(DatFormat, BlankLinesSeparateFibersAndBundles)
{
  // Comments, CRLF, tabs, leading blank lines, a run of three blank lines, a one-point fiber.
  const std::string text = "\n\n# written by hand\n"
                           "0 0 0 1\r\n"
                           "1\t0 0 1\n"
                           "\n"
                           "# a comment between fibers\n"
                           "2 0 0 0.5\n"
                           "3 0 0 +0.5\n"
                           "\n"
                           "\n"
                           "\n"
                           "9 9 9 2\n" // one point: dropped, still fiber 2 of the file
                           "\n"
                           "5 5 5 1e-1\n"
                           "6 5 5 1E-1\n"; // no trailing newline or blank line
  const FiberReadResult r = readString(text);
  ASSERT_TRUE(r.ok()) << r.error;
  ASSERT_EQ(r.model.fibers.size(), 3u);
  EXPECT_EQ(r.droppedFibers, 1u);
  EXPECT_EQ(r.model.fibers[0].id, 0);
  EXPECT_EQ(r.model.fibers[0].bundle, 0);
  EXPECT_EQ(r.model.fibers[0].points[1], (Vec3{ 1, 0, 0 }));
  EXPECT_EQ(r.model.fibers[1].id, 1);
  EXPECT_EQ(r.model.fibers[1].bundle, 0);
  EXPECT_EQ(r.model.fibers[1].radii[1], 0.5);
  EXPECT_EQ(r.model.fibers[2].id, 3);
  EXPECT_EQ(r.model.fibers[2].bundle, 1);
  EXPECT_EQ(r.model.fibers[2].radii[0], 0.1);
  EXPECT_EQ(r.model.fibers[2].points[1].x, 6.0);
  EXPECT_TRUE(validateModel(r.model).empty());
}

TEST(DatFormat, WriterProducesTheFastPliLayout)
{
  // Same layout as fastPLI's writer and fiber_metrics.py write_dat: a blank line after every
  // fiber, one more between bundles, none at the end. Fibers are grouped by ascending bundle.
  FiberModel m;
  m.fibers = { makeFiber(1, { { { 7, 8, 9, 1.25 } }, { { 7, 8, 10, 1.25 } } }),
    makeFiber(0, { { { 1, 2, 3, 0.5 } }, { { 4, 5, 6, 0.5 } } }),
    makeFiber(0, { { { -0.1, 1e-300, 1e300, 3 } }, { { 0, 0, 0, 0.25 } } }) };
  std::ostringstream out;
  ASSERT_EQ(writeFastPliDat(out, m), "");
  EXPECT_EQ(out.str(),
    "1 2 3 0.5\n4 5 6 0.5\n\n"
    "-0.1 1e-300 1e+300 3\n0 0 0 0.25\n\n"
    "\n"
    "7 8 9 1.25\n7 8 10 1.25\n\n");

  const FiberReadResult r = readString(out.str());
  ASSERT_TRUE(r.ok()) << r.error;
  ASSERT_EQ(r.model.fibers.size(), 3u);
  EXPECT_EQ(r.model.fibers[0].bundle, 0);
  EXPECT_EQ(r.model.fibers[1].bundle, 0);
  EXPECT_EQ(r.model.fibers[2].bundle, 1);
  EXPECT_EQ(r.model.fibers[2].points[0], (Vec3{ 7, 8, 9 }));
}

TEST(DatFormat, RoundTripIsBitExact)
{
  // Random magnitudes over many decades and random mantissas: every double must come back with
  // the same bits. Bundles 0..2 in model order, as generators produce them.
  FiberModel m;
  RandomStream rng(7);
  for (int k = 0; k < 30; ++k)
  {
    Fiber f;
    f.id = k;
    f.bundle = k / 10;
    const int n = 2 + static_cast<int>(rng.uniform() * 20);
    for (int i = 0; i < n; ++i)
    {
      Vec3 p;
      for (int a = 0; a < 3; ++a)
      {
        p[a] = (rng.uniform() - 0.5) * std::pow(10.0, rng.uniform(-30, 30));
      }
      f.points.push_back(p);
      f.radii.push_back(rng.uniform() * std::pow(10.0, rng.uniform(-5, 5)) + 1e-300);
    }
    m.fibers.push_back(f);
  }
  std::ostringstream out;
  ASSERT_EQ(writeFastPliDat(out, m), "");
  const FiberReadResult r = readString(out.str());
  ASSERT_TRUE(r.ok()) << r.error;
  ASSERT_EQ(r.model.fibers.size(), m.fibers.size());
  for (std::size_t k = 0; k < m.fibers.size(); ++k)
  {
    const Fiber& a = m.fibers[k];
    const Fiber& b = r.model.fibers[k];
    EXPECT_EQ(b.id, a.id);
    EXPECT_EQ(b.bundle, a.bundle);
    ASSERT_EQ(b.points.size(), a.points.size());
    for (std::size_t i = 0; i < a.points.size(); ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        ASSERT_TRUE(sameBits(a.points[i][c], b.points[i][c])) << "fiber " << k << " point " << i;
      }
      ASSERT_TRUE(sameBits(a.radii[i], b.radii[i]));
    }
  }
}

TEST(DatFormat, ReadsTheFastPliSampleFiles)
{
  // Expected counts from awk over the files (blank-line separated blocks), first/last lines by eye.
  {
    std::ifstream in(dataPath("fastpli/cube.dat"));
    ASSERT_TRUE(in) << dataPath("fastpli/cube.dat");
    const FiberReadResult r = readFastPliDat(in, "cube.dat");
    ASSERT_TRUE(r.ok()) << r.error;
    EXPECT_EQ(r.model.fibers.size(), 100u);
    EXPECT_EQ(r.model.numberOfPoints(), 1994u);
    EXPECT_EQ(r.droppedFibers, 0u);
    EXPECT_EQ(r.model.fibers.front().points.front(), (Vec3{ -6.55, -18.93, -64.98 }));
    EXPECT_EQ(r.model.fibers.front().radii.front(), 3.75);
    EXPECT_EQ(r.model.fibers.back().points.back(), (Vec3{ 51.85, -3.97, 1.94 }));
    EXPECT_EQ(r.model.fibers.back().id, 99);
    for (const Fiber& f : r.model.fibers)
    {
      EXPECT_EQ(f.bundle, 0);
    }
    EXPECT_TRUE(validateModel(r.model).empty());
  }
  {
    std::ifstream in(dataPath("fastpli/fastpli.dat"));
    ASSERT_TRUE(in);
    EXPECT_TRUE(looksLikeFastPliDat(in));
    const FiberReadResult r = readFastPliDat(in, "fastpli.dat");
    ASSERT_TRUE(r.ok()) << r.error;
    EXPECT_EQ(r.model.fibers.size(), 11u);
    EXPECT_EQ(r.model.numberOfPoints(), 53u);
    EXPECT_EQ(r.model.fibers[0].points[2].y, 292.66700000000003);
    EXPECT_EQ(r.model.fibers.back().points.back(), (Vec3{ 2006.667, 16.666999999999973, 0.0 }));
    EXPECT_EQ(r.model.fibers.back().radii.back(), 50.0);
  }
}

TEST(DatFormat, BadLinesNameFileLineAndProblem)
{
  struct Case
  {
    const char* text;
    const char* expectLine;
    const char* expectWhat;
  };
  const Case cases[] = {
    { "0 0 0 1\n1 0 0\n", "test.dat line 2:", "found 3" },
    { "0 0 0 1\n1 0 0 1 5\n", "test.dat line 2:", "found 5" },
    { "# c\n0 0 0 1\n1 0 abc 1\n", "test.dat line 3:", "'abc' is not a number" },
    { "0 0 0 1\n1 0 0 1x\n", "test.dat line 2:", "'1x' is not a number" },
    { "0 nan 0 1\n", "test.dat line 1:", "'nan' is not a finite number" },
    { "0 0 inf 1\n", "test.dat line 1:", "'inf' is not a finite number" },
    { "0 0 1e999 1\n", "test.dat line 1:", "'1e999' is not a finite number" },
    { "0 0 0 1\n\n1 1 1 -2\n", "test.dat line 3:", "radius -2 must be > 0" },
    { "0 0 0 0\n", "test.dat line 1:", "radius 0 must be > 0" },
    { "TITLE = \"x\"\n", "test.dat line 1:", "'TITLE' is not a number" },
  };
  for (const Case& c : cases)
  {
    const FiberReadResult r = readString(c.text);
    EXPECT_FALSE(r.ok()) << c.text;
    EXPECT_NE(r.error.find(c.expectLine), std::string::npos) << r.error;
    EXPECT_NE(r.error.find(c.expectWhat), std::string::npos) << r.error;
    EXPECT_TRUE(r.model.fibers.empty());
  }
  // An endless line (binary junk without newlines) is refused without buffering it.
  const FiberReadResult r = readString("0 0 0 1\n" + std::string(100000, '7'));
  EXPECT_NE(r.error.find("test.dat line 2: line is longer than 4096"), std::string::npos)
    << r.error;
}

TEST(DatFormat, WriterRefusesModelsItCannotRoundTrip)
{
  FiberModel m;
  m.fibers = { makeFiber(0, { { { 0, 0, 0, 1 } } }) }; // one point: would be dropped on reading
  std::ostringstream out;
  std::string err = writeFastPliDat(out, m);
  EXPECT_NE(err.find("fiber 0"), std::string::npos) << err;
  EXPECT_NE(err.find("fewer than 2 points"), std::string::npos) << err;
  m.fibers = { makeFiber(0, { { { 0, 0, 0, 1 } }, { { 1, 0, 0, std::nan("") } } }) };
  err = writeFastPliDat(out, m);
  EXPECT_NE(err.find("point 1"), std::string::npos) << err;
  // A failing stream is reported, not ignored.
  std::ostringstream bad;
  bad.setstate(std::ios::badbit);
  m.fibers = { makeFiber(0, { { { 0, 0, 0, 1 } }, { { 1, 0, 0, 1 } } }) };
  EXPECT_NE(writeFastPliDat(bad, m).find("stream failed"), std::string::npos);
}

TEST(DatFormat, SniffingAcceptsFastPliAndRejectsTecplot)
{
  auto sniff = [](const std::string& text)
  {
    std::istringstream in(text);
    in.seekg(0);
    const bool yes = looksLikeFastPliDat(in);
    EXPECT_EQ(in.tellg(), std::streampos(0)) << "position not restored";
    return yes;
  };
  EXPECT_TRUE(sniff("1 2 3 0.5\n4 5 6 0.5\n"));
  EXPECT_TRUE(sniff("\n# comment\n1 2 3 0.5"));
  EXPECT_FALSE(sniff("TITLE = \"Example\"\nVARIABLES = \"X\", \"Y\"\nZONE I=2\n1 2\n3 4\n"));
  EXPECT_FALSE(sniff("VARIABLES = X Y Z R\n1 2 3 0.5\n"));
  EXPECT_FALSE(sniff("1 2 3\n4 5 6\n"));         // 3 columns: a point cloud, not fibers
  EXPECT_FALSE(sniff("1 2 3 -0.5\n"));           // negative radius
  EXPECT_FALSE(sniff("1 2 3 0.5\n1 2 3 nan\n")); // NaN
  EXPECT_FALSE(sniff(""));
  EXPECT_FALSE(sniff("\n\n# only comments\n"));
  EXPECT_FALSE(sniff(std::string("1 2 3 0.5\0\0\0", 12)));
  EXPECT_FALSE(sniff("mrtrix tracks\ndatatype: Float32LE\n"));
  // One bad line among fastPLI points: still ours, so the user sees our line number.
  std::string points;
  for (int i = 0; i < 30; ++i)
  {
    points += std::to_string(i) + " 0 0 0.5\n";
  }
  EXPECT_TRUE(sniff("1 2 abc 0.5\n" + points));
  EXPECT_TRUE(sniff(points.substr(0, 24) + "1 2 3\n" + points));
  // A Tecplot header stays Tecplot's even when its zone holds 4 numbers per line.
  EXPECT_FALSE(sniff("TITLE = \"x\"\nVARIABLES = \"X\" \"Y\" \"Z\" \"R\"\nZONE I=30\n" + points));
  EXPECT_FALSE(sniff("zone t=\"a\"\n" + points));
  EXPECT_FALSE(sniff("a b c d\nx y z w\n1 2 3 0.5\n")); // mostly not points
}

TEST(DatFormat, GarbageIsQuotedEscapedNeverEchoedRaw)
{
  // A binary or damaged file: the message must not carry its raw bytes (an escape sequence would
  // act on the terminal that shows it), only printable ASCII, and a long token is cut short.
  const std::string garbage =
    std::string("1 2 \x1b[2J\x1b]0;owned\x07\xff\x01") + std::string(200, 'x') + " 4\n";
  std::istringstream in(garbage);
  const FiberReadResult r = readFastPliDat(in, "broken.dat");
  ASSERT_FALSE(r.ok());
  for (const char c : r.error)
  {
    const unsigned char u = static_cast<unsigned char>(c);
    EXPECT_TRUE(u >= 0x20 && u < 0x7f) << "raw byte " << static_cast<int>(u) << " in: " << r.error;
  }
  EXPECT_NE(r.error.find("\\x1b[2J\\x1b]0;owned\\x07\\xff\\x01"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("..."), std::string::npos) << r.error;
  EXPECT_LT(r.error.size(), 160u) << r.error;
}
