// Optics (docs/pli-simulation.md §5, test vectors S-10): Gaussian PSF with mirrored edges, binning
// to CCD pixels, Gamma–Poisson camera noise and its reproducibility.
#include "PLI/Optics.h"
#include "PLITestUtil.h"
#include "Util/Random.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace fiberpli;
using namespace fiberpli::pli;
using namespace plitest;

namespace
{
Stack image(std::int64_t nx, std::int64_t ny, int nr = 1)
{
  Stack s;
  s.resize(GridRange{ 0, nx, 0, ny }, nr);
  return s;
}

Stack blurAll(const Stack& in, double sigma)
{
  Stack out;
  const Status st = blurStack(in, in.nx, in.ny, sigma, GridRange{ 0, in.nx, 0, in.ny }, out);
  EXPECT_TRUE(st.ok()) << st.error;
  return out;
}
} // namespace

TEST(PLIOptics, S10BlurImpulses)
{
  Stack a = image(9, 9);
  a.at(4, 4, 0) = 1.0;
  Stack b = blurAll(a, 1.0);
  EXPECT_NEAR(b.at(4, 4, 0), 0.1591558917, 1e-10);
  EXPECT_NEAR(b.at(5, 4, 0), 0.0965329280, 1e-10);
  double sum = 0;
  for (double v : b.data)
    sum += v;
  EXPECT_NEAR(sum, 1.0, 1e-12);

  Stack c = image(9, 9);
  c.at(0, 0, 0) = 1.0;
  Stack d = blurAll(c, 1.0);
  EXPECT_NEAR(d.at(0, 0, 0), 0.4107719283, 1e-10);
  sum = 0;
  for (double v : d.data)
    sum += v;
  EXPECT_NEAR(sum, 1.0, 1e-12);

  Stack e = image(6, 1);
  e.at(0, 0, 0) = 1.0;
  Stack f = blurAll(e, 1.0);
  const double ref[6] = { 0.640914915, 0.295962573, 0.058422989, 0.004565692, 0.000133831, 0 };
  for (int i = 0; i < 6; ++i)
    EXPECT_NEAR(f.at(i, 0, 0), ref[i], 1e-9);
  EXPECT_EQ(gaussianWeights(2.84).size(), 23u); // R = 11 (σ_px 0.71, pixel 20, voxel 5)
}

TEST(PLIOptics, BlurMatchesTheDefinitionOnRandomImages)
{
  RandomStream rng(5);
  Stack a = image(13, 7, 2);
  for (double& v : a.data)
    v = rng.uniform(0, 100);
  for (double sigma : { 0.7, 1.9, 4.0 }) // 4.0: kernel longer than the 7-pixel axis
  {
    const Stack b = blurAll(a, sigma);
    const std::vector<double> w = gaussianWeights(sigma);
    const int R = static_cast<int>(w.size() / 2);
    for (int j = 0; j < 7; ++j)
      for (int i = 0; i < 13; ++i)
        for (int k = 0; k < 2; ++k)
        {
          double ref = 0;
          for (int n = -R; n <= R; ++n)
            for (int m = -R; m <= R; ++m)
              ref += w[m + R] * w[n + R] * a.at(mirrorIndex(i + m, 13), mirrorIndex(j + n, 7), k);
          EXPECT_NEAR(b.at(i, j, k), ref, 1e-12);
        }
  }
  EXPECT_EQ(mirrorIndex(-1, 5), 0);
  EXPECT_EQ(mirrorIndex(-2, 5), 1);
  EXPECT_EQ(mirrorIndex(5, 5), 4);
  EXPECT_EQ(mirrorIndex(12, 5), 2);
}

TEST(PLIOptics, S10Binning)
{
  Stack a = image(4, 4);
  for (int v = 0; v < 16; ++v)
    a.data[v] = v;
  Stack out;
  ASSERT_TRUE(binStack(a, 4, 4, 0.5, { 0, 2, 0, 2 }, out).ok());
  EXPECT_EQ(out.at(0, 0, 0), 2.5);
  EXPECT_EQ(out.at(1, 0, 0), 4.5);
  EXPECT_EQ(out.at(0, 1, 0), 10.5);
  EXPECT_EQ(out.at(1, 1, 0), 12.5);
  EXPECT_EQ(pixelCount(4, 1.0 / 3.0), 1);
  ASSERT_TRUE(binStack(a, 4, 4, 1.0 / 3.0, { 0, 1, 0, 1 }, out).ok());
  EXPECT_EQ(out.at(0, 0, 0), 5.0);
  Stack b = image(5, 5);
  for (int v = 0; v < 25; ++v)
    b.data[v] = v;
  ASSERT_TRUE(binStack(b, 5, 5, 0.4, { 0, 2, 0, 2 }, out).ok());
  EXPECT_DOUBLE_EQ(out.at(0, 0, 0), 3);
  EXPECT_DOUBLE_EQ(out.at(1, 0, 0), 5.5);
  EXPECT_DOUBLE_EQ(out.at(0, 1, 0), 15.5);
  EXPECT_DOUBLE_EQ(out.at(1, 1, 0), 18);
}

TEST(PLIOptics, UniformStaysUniform)
{
  Stack a = image(17, 11, 3);
  for (double& v : a.data)
    v = 1234.5;
  const Stack b = blurAll(a, 2.3);
  Stack c;
  ASSERT_TRUE(binStack(b, 17, 11, 0.3, { 0, pixelCount(17, 0.3), 0, pixelCount(11, 0.3) }, c).ok());
  for (double v : c.data)
    EXPECT_NEAR(v, 1234.5, 1234.5 * 1e-12);
}

TEST(PLIOptics, S10NoiseStatistics)
{
  struct Case
  {
    double I, g, meanTol, varRatio, varTol;
  };
  const Case cases[] = { { 1000, 3, 0.5, 3, 0.05 }, { 50, 3, 0.1, 3, 0.1 },
    { 1000, 1, 0.5, 1, 0.02 } };
  const int n = 400000;
  for (const Case& c : cases)
  {
    double s = 0, s2 = 0;
    for (int i = 0; i < n; ++i)
    {
      const double x = sampleCounts(c.I, c.g, 11, static_cast<std::uint64_t>(i), 0);
      ASSERT_EQ(x, std::floor(x));
      s += x;
      s2 += x * x;
    }
    const double mean = s / n, var = s2 / n - mean * mean;
    EXPECT_NEAR(mean, c.I, c.meanTol) << "I " << c.I << " g " << c.g;
    EXPECT_NEAR(var / c.I, c.varRatio, c.varTol) << "I " << c.I << " g " << c.g;
  }
  EXPECT_EQ(sampleCounts(-3, 3, 1, 2, 3), -3);
  EXPECT_EQ(sampleCounts(700, 0, 1, 2, 3), 700);
}

TEST(PLIOptics, S10NoisySingleVoxelEpa)
{
  const int N = 18, side = 100;
  Stack px = image(side, side, N);
  const double s = -0.6579387259, phi = 30 * M_PI / 180;
  for (int j = 0; j < side; ++j)
    for (int i = 0; i < side; ++i)
      for (int k = 0; k < N; ++k)
        px.at(i, j, k) = 6500 * (1 - s * std::sin(2 * (k * M_PI / N - phi)));
  Stack again = px;
  addNoise(px, 3, 42, 0, side, 1);
  addNoise(again, 3, 42, 0, side, 2);
  EXPECT_EQ(px.data, again.data); // 1 vs 2 threads
  double mT = 0, mD = 0, mR = 0, sD = 0, sR = 0;
  const int n = side * side;
  for (int p = 0; p < n; ++p)
  {
    const Epa e = epa(&px.data[p * N], N);
    mT += e.T / n;
    mD += e.dirDeg / n;
    mR += e.ret / n;
    sD += (e.dirDeg - 30) * (e.dirDeg - 30) / n;
  }
  for (int p = 0; p < n; ++p)
  {
    const Epa e = epa(&px.data[p * N], N);
    sR += (e.ret - mR) * (e.ret - mR) / n;
  }
  EXPECT_NEAR(mT, 13000, 5);
  EXPECT_NEAR(mD, 30, 0.02);
  EXPECT_GT(std::sqrt(sD), 0.25);
  EXPECT_LT(std::sqrt(sD), 0.37);
  EXPECT_NEAR(mR, 0.6581, 0.0005);
  EXPECT_NEAR(std::sqrt(sR), 0.0063, 0.0010);
}

TEST(PLIOptics, NoiseKeyedByGlobalPixel)
{
  // A piece of the image gets the same noise as the same pixels of the whole image.
  Stack whole = image(8, 6, 4);
  for (double& v : whole.data)
    v = 900;
  Stack piece;
  piece.resize(GridRange{ 3, 7, 2, 5 }, 4);
  for (double& v : piece.data)
    v = 900;
  addNoise(whole, 3, 9, 2, 8, 1);
  addNoise(piece, 3, 9, 2, 8, 1);
  for (int j = 2; j < 5; ++j)
    for (int i = 3; i < 7; ++i)
      for (int k = 0; k < 4; ++k)
        EXPECT_EQ(piece.at(i, j, k), whole.at(i, j, k));
  Stack other = image(8, 6, 4);
  for (double& v : other.data)
    v = 900;
  addNoise(other, 3, 10, 2, 8, 1);
  EXPECT_NE(other.data, whole.data);
}
