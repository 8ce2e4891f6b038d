// TrackVis .trk reader (TrkFormat.h, docs/api.md §4): hand-made headers with the
// fields at the spec's byte offsets, the voxmm -> world transform on cases computed by hand, both
// byte orders, scalars/properties skipped, bad files with byte offsets, sniffing.
#include "IO/TrkFormat.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <vector>

using namespace fiberpli;

namespace
{

struct TrkSpec
{
  char magic[6] = { 'T', 'R', 'A', 'C', 'K', 0 };
  std::int16_t dim[3] = { 10, 20, 30 };
  float voxelSize[3] = { 2, 3, 4 };
  std::int16_t nScalars = 0;
  std::int16_t nProperties = 0;
  float voxToRas[16] = { 1, 0, 0, 10, 0, 1, 0, 20, 0, 0, 1, 30, 0, 0, 0, 1 };
  char voxelOrder[4] = { 'R', 'A', 'S', 0 };
  std::int32_t nCount = 0;
  std::int32_t version = 2;
  std::int32_t hdrSize = 1000;
};

/// Little-endian host assumed (checked in TckFormat tests); bigEndian swaps every field.
template <typename T>
void put(std::string& buf, std::size_t offset, T value, bool bigEndian)
{
  unsigned char b[sizeof(T)];
  std::memcpy(b, &value, sizeof(T));
  if (bigEndian)
  {
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i)
    {
      std::swap(b[i], b[sizeof(T) - 1 - i]);
    }
  }
  if (buf.size() < offset + sizeof(T))
  {
    buf.resize(offset + sizeof(T), '\0');
  }
  std::memcpy(&buf[offset], b, sizeof(T));
}

std::string header(const TrkSpec& s, bool be = false)
{
  std::string h(1000, '\0');
  std::memcpy(&h[0], s.magic, 6);
  for (int a = 0; a < 3; ++a)
  {
    put(h, 6 + 2 * a, s.dim[a], be);
    put(h, 12 + 4 * a, s.voxelSize[a], be);
  }
  put(h, 36, s.nScalars, be);
  std::memcpy(&h[38], "fa", 2); // scalar_name[0]
  put(h, 238, s.nProperties, be);
  for (int i = 0; i < 16; ++i)
  {
    put(h, 440 + 4 * i, s.voxToRas[i], be);
  }
  std::memcpy(&h[948], s.voxelOrder, 4);
  put(h, 988, s.nCount, be);
  put(h, 992, s.version, be);
  put(h, 996, s.hdrSize, be);
  return h;
}

void track(std::string& buf, const std::vector<float>& values, std::int32_t n, bool be = false)
{
  std::size_t at = buf.size();
  put(buf, at, n, be);
  for (float v : values)
  {
    at = buf.size();
    put(buf, at, v, be);
  }
}

FiberReadResult readBytes(const std::string& bytes, double radius = 0.5)
{
  std::istringstream in(bytes);
  return readTrk(in, "t.trk", radius);
}

void expectNear(const Vec3& got, const Vec3& want)
{
  EXPECT_NEAR(got.x, want.x, 1e-12);
  EXPECT_NEAR(got.y, want.y, 1e-12);
  EXPECT_NEAR(got.z, want.z, 1e-12);
}

/// voxel_size (2,3,4), vox_to_ras = identity + translation (10,20,30), RAS; one scalar per point
/// and two properties per track. Track 0: p = (3, 4.5, 6) and (1, 1.5, 2); track 1 has one point.
std::string sampleFile(bool be)
{
  TrkSpec s;
  s.nScalars = 1;
  s.nProperties = 2;
  s.nCount = 2;
  std::string f = header(s, be);
  track(f, { 3, 4.5f, 6, 99, 1, 1.5f, 2, 98, 7, 8 }, 2, be);
  track(f, { 5, 5, 5, 97, 9, 9 }, 1, be);
  return f;
}

} // namespace

TEST(TrkFormat, HeaderOffsetsFollowTheSpec)
{
  // The hand encoder above, checked against the field offsets of the TrackVis format page.
  const std::string h = header(TrkSpec{});
  ASSERT_EQ(h.size(), 1000u);
  EXPECT_EQ(h.substr(0, 5), "TRACK");
  EXPECT_EQ(static_cast<unsigned char>(h[6]), 10);     // dim[0] low byte
  EXPECT_EQ(static_cast<unsigned char>(h[15]), 0x40);  // voxel_size[0] = 2.0f = 00 00 00 40
  EXPECT_EQ(static_cast<unsigned char>(h[443]), 0x3f); // vox_to_ras[0][0] = 1.0f = 00 00 80 3f
  EXPECT_EQ(h.substr(948, 3), "RAS");
  EXPECT_EQ(static_cast<unsigned char>(h[996]), 0xe8); // 1000 = 0x3e8
  EXPECT_EQ(static_cast<unsigned char>(h[997]), 0x03);
}

TEST(TrkFormat, VoxmmToWorldWithVoxToRas)
{
  for (bool be : { false, true })
  {
    const FiberReadResult r = readBytes(sampleFile(be), 0.25);
    ASSERT_TRUE(r.ok()) << r.error;
    ASSERT_EQ(r.model.fibers.size(), 1u);
    EXPECT_EQ(r.droppedFibers, 1u);
    const Fiber& f = r.model.fibers[0];
    ASSERT_EQ(f.points.size(), 2u);
    // v = p / voxel_size - 0.5 = (1, 1, 1) and (0, 0, 0); world = v + (10, 20, 30).
    expectNear(f.points[0], { 11, 21, 31 });
    expectNear(f.points[1], { 10, 20, 30 });
    EXPECT_EQ(f.radii, (std::vector<double>{ 0.25, 0.25 }));
    EXPECT_EQ(f.id, 0);
  }
}

TEST(TrkFormat, ScaledRotatedAffine)
{
  // vox_to_ras maps voxel axis i -> world y scaled by 2, j -> world -x scaled by 3 (an LPS-like
  // rotation), k -> z by 4, offset (1,2,3); voxel_order "ALS" says the same. Voxel (1,1,1) is at
  // p = (1.5*2, 1.5*3, 1.5*4); world = (-3*1 + 1, 2*1 + 2, 4*1 + 3) = (-2, 4, 7).
  TrkSpec s;
  const float A[16] = { 0, -3, 0, 1, 2, 0, 0, 2, 0, 0, 4, 3, 0, 0, 0, 1 };
  std::memcpy(s.voxToRas, A, sizeof A);
  std::memcpy(s.voxelOrder, "ALS", 4);
  std::string f = header(s);
  track(f, { 3, 4.5f, 6, 1, 1.5f, 2 }, 2);
  const FiberReadResult r = readBytes(f);
  ASSERT_TRUE(r.ok()) << r.error;
  expectNear(r.model.fibers[0].points[0], { -2, 4, 7 });
  expectNear(r.model.fibers[0].points[1], { 1, 2, 3 });
}

TEST(TrkFormat, VoxelOrderDisagreeingWithAffineFlipsAxes)
{
  // Points stored in LPS voxel order, affine is RAS (identity + offset): nibabel flips i and j,
  // v' = (dim - 1 - v). Voxel (1,1,1) -> (10-1-1, 20-1-1, 1) = (8, 18, 1) -> + (10, 20, 30).
  TrkSpec s;
  std::memcpy(s.voxelOrder, "LPS", 4);
  std::string f = header(s);
  track(f, { 3, 4.5f, 6, 1, 1.5f, 2 }, 2);
  FiberReadResult r = readBytes(f);
  ASSERT_TRUE(r.ok()) << r.error;
  expectNear(r.model.fibers[0].points[0], { 18, 38, 31 });
  expectNear(r.model.fibers[0].points[1], { 19, 39, 30 });

  // Empty voxel_order means LPS (nibabel's default): same result.
  std::memset(s.voxelOrder, 0, 4);
  f = header(s);
  track(f, { 3, 4.5f, 6, 1, 1.5f, 2 }, 2);
  r = readBytes(f);
  ASSERT_TRUE(r.ok()) << r.error;
  expectNear(r.model.fibers[0].points[0], { 18, 38, 31 });
}

TEST(TrkFormat, MissingVoxToRasScalesByVoxelSize)
{
  // vox_to_ras[3][3] == 0: diag(voxel_size) is used, so world = p - voxel_size / 2.
  TrkSpec s;
  std::memset(s.voxToRas, 0, sizeof s.voxToRas);
  s.version = 1;
  std::string f = header(s);
  track(f, { 3, 4.5f, 6, 1, 1.5f, 2, 0, 0, 0 }, 3);
  const FiberReadResult r = readBytes(f);
  ASSERT_TRUE(r.ok()) << r.error;
  expectNear(r.model.fibers[0].points[0], { 2, 3, 4 });
  expectNear(r.model.fibers[0].points[2], { -1, -1.5, -2 });
}

TEST(TrkFormat, BadFilesNameTheByteOffset)
{
  const std::string good = sampleFile(false);
  ASSERT_TRUE(readBytes(good).ok());
  auto with = [&](TrkSpec s, const std::string& body) { return header(s) + body; };
  std::string oneTrack;
  track(oneTrack, { 3, 4.5f, 6, 1, 1.5f, 2 }, 2);
  struct Case
  {
    std::string bytes;
    std::string expect;
  };
  TrkSpec magic;
  magic.magic[0] = 'X';
  TrkSpec hdr;
  hdr.hdrSize = 999;
  TrkSpec version;
  version.version = 3;
  TrkSpec voxel;
  voxel.voxelSize[1] = 0;
  TrkSpec scalars;
  scalars.nScalars = -2;
  TrkSpec props;
  props.nProperties = -1;
  TrkSpec nanAffine;
  nanAffine.voxToRas[5] = std::numeric_limits<float>::quiet_NaN();
  TrkSpec order;
  std::memcpy(order.voxelOrder, "RRS", 4);
  TrkSpec moreDeclared;
  moreDeclared.nCount = 2;
  TrkSpec fewerDeclared;
  fewerDeclared.nCount = 1;
  TrkSpec hugeCount;
  hugeCount.nCount = 2000000000;
  TrkSpec negCount;
  negCount.nCount = -5;
  std::string hugeTrack;
  track(hugeTrack, { 1, 2, 3 }, 2147483647);
  std::string negTrack;
  track(negTrack, {}, -1);
  std::string nanTrack;
  track(nanTrack, { 1, 2, 3, 4, std::numeric_limits<float>::infinity(), 6 }, 2);
  const std::vector<Case> cases = {
    { good.substr(0, 999), "t.trk byte 999: file ends inside the 1000-byte TrackVis header" },
    { "", "t.trk byte 0: file ends inside" },
    { with(magic, oneTrack), "t.trk byte 0: not a TrackVis file" },
    { with(hdr, oneTrack), "t.trk byte 996: hdr_size is 999, must be 1000" },
    { with(version, oneTrack), "t.trk byte 992: version 3 is not supported" },
    { with(voxel, oneTrack), "t.trk byte 16: voxel_size[1] is 0" },
    { with(scalars, oneTrack), "t.trk byte 36: n_scalars -2 is negative" },
    { with(props, oneTrack), "t.trk byte 238: n_properties -1 is negative" },
    { with(nanAffine, oneTrack), "t.trk byte 460: vox_to_ras holds a non-finite value" },
    { with(order, oneTrack), "t.trk byte 948: voxel_order 'RRS'" },
    { with(moreDeclared, oneTrack),
      "t.trk byte 1028: header n_count 2 but the file ends after 1 tracks" },
    { with(fewerDeclared, oneTrack + oneTrack),
      "t.trk byte 1028: header n_count 1 but 28 more bytes follow track 0" },
    { with(hugeCount, oneTrack),
      "t.trk byte 988: n_count 2000000000 tracks cannot fit in the 28 bytes" },
    { with(negCount, oneTrack), "t.trk byte 988: n_count -5 is negative" },
    { with(TrkSpec{}, hugeTrack),
      "t.trk byte 1000: track 0 declares 2147483647 points (25769803764 bytes) but only 12 bytes "
      "remain" },
    { with(TrkSpec{}, negTrack), "t.trk byte 1000: track 0 has a negative point count -1" },
    { with(TrkSpec{}, oneTrack + nanTrack),
      "t.trk byte 1048: track 1 point 1 has a non-finite coordinate" },
    { with(TrkSpec{}, oneTrack.substr(0, 27)),
      "t.trk byte 1000: track 0 declares 2 points (24 bytes) but only 23 bytes remain" },
    { with(TrkSpec{}, oneTrack + "ab"),
      "t.trk byte 1028: file ends inside the point count of track 1" },
  };
  for (const Case& c : cases)
  {
    const FiberReadResult r = readBytes(c.bytes);
    EXPECT_FALSE(r.ok()) << c.expect;
    EXPECT_NE(r.error.find(c.expect), std::string::npos)
      << "got: " << r.error << "\nwanted: " << c.expect;
    EXPECT_TRUE(r.model.fibers.empty());
  }
  EXPECT_NE(readBytes(good, -1.0).error.find("DefaultRadius -1"), std::string::npos);
}

TEST(TrkFormat, ReadsTheCommittedSampleFile)
{
  // Testing/Data/tracks/sample.trk was written with Python's struct module (an encoder
  // independent of ours): the same content as sampleFile(false).
  const std::string path = std::string(FIBERPLI_TEST_DATA_DIR) + "/tracks/sample.trk";
  std::ifstream in(path, std::ios::binary);
  ASSERT_TRUE(in) << path;
  std::ostringstream bytes;
  bytes << in.rdbuf();
  EXPECT_EQ(bytes.str(), sampleFile(false)) << "hand encoder and Python's struct disagree";
  std::istringstream again(bytes.str());
  EXPECT_TRUE(looksLikeTrk(again));
  const FiberReadResult r = readTrk(again, path, 1.0);
  ASSERT_TRUE(r.ok()) << r.error;
  expectNear(r.model.fibers[0].points[0], { 11, 21, 31 });
}

TEST(TrkFormat, Sniffing)
{
  auto sniff = [](const std::string& s)
  {
    std::istringstream in(s);
    const bool yes = looksLikeTrk(in);
    EXPECT_EQ(in.tellg(), std::streampos(0));
    return yes;
  };
  EXPECT_TRUE(sniff(sampleFile(false)));
  EXPECT_TRUE(sniff(sampleFile(true)));
  EXPECT_TRUE(sniff(header(TrkSpec{})));
  EXPECT_FALSE(sniff(sampleFile(false).substr(0, 999)));
  TrkSpec bad;
  bad.hdrSize = 1001;
  EXPECT_FALSE(sniff(header(bad)));
  EXPECT_FALSE(sniff("mrtrix tracks\n"));
  EXPECT_FALSE(sniff(""));
}
