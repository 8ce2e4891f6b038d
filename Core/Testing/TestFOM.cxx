// Fiber orientation map colours (docs/pli-analysis.md §4, test vector A-6) and the colour legend.
#include "Analysis/FiberOrientationMap.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

using namespace fiberpli;

namespace
{
struct Expect
{
  double d, i;
  int hsv[3];
  int rgb[3];
};

// A-6, verbatim.
const Expect kA6[] = {
  { 0, 0, { 255, 0, 0 }, { 255, 0, 0 } },
  { 15, 0, { 255, 127, 0 }, { 246, 65, 0 } },
  { 30, 0, { 255, 255, 0 }, { 220, 127, 0 } },
  { 45, 0, { 127, 255, 0 }, { 180, 180, 0 } },
  { 60, 0, { 0, 255, 0 }, { 127, 220, 0 } },
  { 90, 0, { 0, 255, 255 }, { 0, 255, 0 } },
  { 120, 0, { 0, 0, 255 }, { 127, 220, 0 } },
  { 150, 0, { 255, 0, 255 }, { 220, 127, 0 } },
  { 179, 0, { 255, 0, 8 }, { 254, 4, 0 } },
  { 0, 45, { 127, 0, 0 }, { 180, 0, 180 } },
  { 90, 30, { 0, 170, 170 }, { 0, 220, 127 } },
  { 30, 60, { 85, 85, 0 }, { 110, 63, 220 } },
  { 30, -60, { 85, 85, 0 }, { 110, 63, 220 } },
};

void expectColor(Rgb8 c, const int e[3], const char* what, double d, double i)
{
  EXPECT_EQ(int(c.r), e[0]) << what << " d=" << d << " i=" << i;
  EXPECT_EQ(int(c.g), e[1]) << what << " d=" << d << " i=" << i;
  EXPECT_EQ(int(c.b), e[2]) << what << " d=" << d << " i=" << i;
}
} // namespace

TEST(FOM, ColoursOfKnownAnglesA6)
{
  for (const Expect& e : kA6)
  {
    expectColor(fomColor(e.d, e.i, FomScheme::HsvBlack), e.hsv, "HSV-black", e.d, e.i);
    expectColor(fomColor(e.d, e.i, FomScheme::Rgb), e.rgb, "RGB", e.d, e.i);
  }
  const int black[3] = { 0, 0, 0 }, blue[3] = { 0, 0, 255 };
  for (double d : { 0.0, 33.0, 90.0, 179.5 })
  {
    expectColor(fomColor(d, 90, FomScheme::HsvBlack), black, "HSV-black", d, 90);
    expectColor(fomColor(d, 90, FomScheme::Rgb), blue, "RGB", d, 90);
    expectColor(fomColor(d, -90, FomScheme::Rgb), blue, "RGB", d, -90);
  }
  expectColor(fomColor(NAN, 10, FomScheme::HsvBlack), black, "HSV-black", NAN, 10);
  expectColor(fomColor(10, NAN, FomScheme::Rgb), black, "RGB", 10, NAN);
  expectColor(fomColor(NAN, NAN, FomScheme::Rgb), black, "RGB", NAN, NAN);
}

TEST(FOM, DirectionIsAnAxisModulo180)
{
  for (FomScheme s : { FomScheme::HsvBlack, FomScheme::Rgb })
  {
    for (double d : { 0.0, 15.0, 30.0, 45.0, 90.0, 150.0 })
    {
      const Rgb8 a = fomColor(d, 20, s), b = fomColor(d + 180, 20, s), c = fomColor(d - 180, 20, s);
      EXPECT_EQ(a.r, b.r);
      EXPECT_EQ(a.g, b.g);
      EXPECT_EQ(a.b, b.b);
      EXPECT_EQ(a.r, c.r);
      EXPECT_EQ(a.g, c.g);
      EXPECT_EQ(a.b, c.b);
    }
  }
}

// A-8's expected FOM pixel: d 30°, i 20° → H 60°, V = 1 − 20/90 → (198, 198, 0).
TEST(FOM, MapOfArraysMatchesPerPixelColours)
{
  std::vector<double> d, i;
  for (const Expect& e : kA6)
  {
    d.push_back(e.d);
    i.push_back(e.i);
  }
  d.push_back(30);
  i.push_back(20);
  std::vector<std::uint8_t> rgb1(3 * d.size()), rgb2(3 * d.size());
  ASSERT_EQ(fomMap(d.data(), i.data(), d.size(), FomScheme::HsvBlack, 1, rgb1.data()), "");
  ASSERT_EQ(fomMap(d.data(), i.data(), d.size(), FomScheme::HsvBlack, 2, rgb2.data()), "");
  EXPECT_EQ(rgb1, rgb2);
  for (std::size_t p = 0; p + 1 < d.size(); ++p)
  {
    EXPECT_EQ(int(rgb1[3 * p]), kA6[p].hsv[0]);
    EXPECT_EQ(int(rgb1[3 * p + 1]), kA6[p].hsv[1]);
    EXPECT_EQ(int(rgb1[3 * p + 2]), kA6[p].hsv[2]);
  }
  const std::size_t last = 3 * (d.size() - 1);
  EXPECT_EQ(int(rgb1[last]), 198);
  EXPECT_EQ(int(rgb1[last + 1]), 198);
  EXPECT_EQ(int(rgb1[last + 2]), 0);
  EXPECT_NE(fomMap(nullptr, i.data(), 1, FomScheme::Rgb, 1, rgb1.data()), "");
}

TEST(FOM, SchemeNamesAreTheApiStrings)
{
  FomScheme s = FomScheme::Rgb;
  ASSERT_TRUE(parseFomScheme("HSV-black", s));
  EXPECT_EQ(s, FomScheme::HsvBlack);
  ASSERT_TRUE(parseFomScheme("RGB", s));
  EXPECT_EQ(s, FomScheme::Rgb);
  EXPECT_FALSE(parseFomScheme("hsv", s));
  EXPECT_STREQ(fomSchemeName(FomScheme::HsvBlack), "HSV-black");
  EXPECT_STREQ(fomSchemeName(FomScheme::Rgb), "RGB");
}

TEST(FOM, LegendIsTheHemisphereSeenFromAbove)
{
  const int n = 101; // odd: the centre pixel is exactly (0, 0), the vertical axis
  std::vector<std::uint8_t> hsv, rgb;
  ASSERT_EQ(fomLegend(n, FomScheme::HsvBlack, hsv), "");
  ASSERT_EQ(fomLegend(n, FomScheme::Rgb, rgb, { 7, 8, 9 }), "");
  ASSERT_EQ(hsv.size(), 3u * n * n);
  auto at = [&](const std::vector<std::uint8_t>& img, int col, int row, int c)
  { return int(img[3 * (static_cast<std::size_t>(row) * n + col) + c]); };
  const int mid = n / 2;
  // Centre: vertical fiber → black (HSV-black) / blue (RGB).
  EXPECT_EQ(at(hsv, mid, mid, 0) + at(hsv, mid, mid, 1) + at(hsv, mid, mid, 2), 0);
  EXPECT_EQ(at(rgb, mid, mid, 2), 255);
  EXPECT_EQ(at(rgb, mid, mid, 0) + at(rgb, mid, mid, 1), 0);
  // Right rim (+x, nearly in-plane): red; top rim (+y): cyan in HSV-black, green in RGB.
  EXPECT_GT(at(hsv, n - 1, mid, 0), 200);
  EXPECT_LT(at(hsv, n - 1, mid, 1), 40);
  EXPECT_GT(at(hsv, mid, n - 1, 1), 200);
  EXPECT_GT(at(hsv, mid, n - 1, 2), 200);
  EXPECT_GT(at(rgb, mid, n - 1, 1), 200);
  EXPECT_LT(at(rgb, mid, n - 1, 0), 5);
  // An axis has no sign: (x, y) and (−x, −y) show the same colour.
  for (int row = 0; row < n; ++row)
  {
    for (int col = 0; col < n; ++col)
    {
      if (row == mid && col == mid)
      {
        continue;
      }
      for (int c = 0; c < 3; ++c)
      {
        ASSERT_EQ(at(hsv, col, row, c), at(hsv, n - 1 - col, n - 1 - row, c)) << col << " " << row;
      }
    }
  }
  // Corners lie outside the disc: background.
  EXPECT_EQ(at(hsv, 0, 0, 0), 255);
  EXPECT_EQ(at(rgb, 0, n - 1, 0), 7);
  EXPECT_EQ(at(rgb, n - 1, 0, 2), 9);
  EXPECT_NE(fomLegend(0, FomScheme::Rgb, rgb), "");
}

TEST(FOM, MaskBlackensBackgroundByRetardationOrTransmittance)
{
  const double retardation[4] = { 0.0, 0.049, 0.05, std::nan("") };
  const double transmittance[4] = { 13000, 12000.5, 9000, 12000 };
  for (FomMask mask : { FomMask::None, FomMask::Retardation, FomMask::Transmittance })
  {
    std::vector<std::uint8_t> rgb(12, 200), tissue(4, 7);
    const double* values = mask == FomMask::Transmittance ? transmittance : retardation;
    const double threshold = mask == FomMask::Transmittance ? 12000.0 : 0.05;
    ASSERT_TRUE(fomApplyMask(values, 4, mask, threshold, rgb.data(), tissue.data()).empty());
    // None keeps all; retardation keeps >= 0.05 (NaN is background); transmittance keeps <= 12000.
    const std::vector<int> keep = mask == FomMask::None ? std::vector<int>{ 1, 1, 1, 1 }
      : mask == FomMask::Retardation                    ? std::vector<int>{ 0, 0, 1, 0 }
                                                        : std::vector<int>{ 0, 0, 1, 1 };
    for (int p = 0; p < 4; ++p)
    {
      EXPECT_EQ(tissue[p], keep[p]) << int(mask) << " pixel " << p;
      for (int c = 0; c < 3; ++c)
      {
        EXPECT_EQ(rgb[3 * p + c], keep[p] ? 200 : 0);
      }
    }
  }
  std::vector<std::uint8_t> rgb(3);
  EXPECT_FALSE(fomApplyMask(nullptr, 1, FomMask::Retardation, 0.1, rgb.data(), nullptr).empty());
  EXPECT_FALSE(
    fomApplyMask(retardation, 1, FomMask::Retardation, std::nan(""), rgb.data(), nullptr).empty());
}

TEST(FOM, MaskThresholdIsAFractionOfTheLargestValue)
{
  // The reference ignores NaN and infinities; none finite gives -inf.
  const double values[5] = { 0.2, std::nan(""), 0.8, std::numeric_limits<double>::infinity(), 0.5 };
  EXPECT_EQ(fomMaskReference(values, 5), 0.8);
  const double none[2] = { std::nan(""), -std::numeric_limits<double>::infinity() };
  EXPECT_EQ(fomMaskReference(none, 2), -std::numeric_limits<double>::infinity());
  EXPECT_EQ(fomMaskReference(nullptr, 0), -std::numeric_limits<double>::infinity());
  double t = -1.0;
  // Retardation: below f·L is background; transmittance: above (1 − f)·L.
  ASSERT_TRUE(fomMaskThreshold(FomMask::Retardation, 0.25, 0.8, t).empty());
  EXPECT_DOUBLE_EQ(t, 0.2);
  ASSERT_TRUE(fomMaskThreshold(FomMask::Transmittance, 0.25, 13000.0, t).empty());
  EXPECT_DOUBLE_EQ(t, 9750.0);
  // The ends: 0 masks only what is exactly background-like, 1 everything but the extreme.
  ASSERT_TRUE(fomMaskThreshold(FomMask::Transmittance, 0.0, 13000.0, t).empty());
  EXPECT_EQ(t, 13000.0);
  ASSERT_TRUE(fomMaskThreshold(FomMask::Retardation, 1.0, 0.8, t).empty());
  EXPECT_EQ(t, 0.8);
  ASSERT_TRUE(
    fomMaskThreshold(FomMask::Transmittance, 0.5, -std::numeric_limits<double>::infinity(), t)
      .empty());
  EXPECT_EQ(t, 0.0);
  for (double bad : { -0.01, 1.01, std::nan("") })
  {
    EXPECT_FALSE(fomMaskThreshold(FomMask::Retardation, bad, 0.8, t).empty()) << bad;
  }
}
