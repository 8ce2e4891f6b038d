// PLI analysis (pli-analysis.md §2, §3; test vectors A-1 … A-5): EPA on equidistant and arbitrary
// polarizer angles, inclination from retardation, and the tilt fit on closed-form views.
#include "Analysis/Epa.h"
#include "Analysis/RetardationInclination.h"

#include "Util/Random.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

using namespace fiberpli;

namespace
{
constexpr double kDeg = M_PI / 180.0;

std::vector<double> anglesDeg(std::initializer_list<double> deg)
{
  std::vector<double> r;
  for (double d : deg)
  {
    r.push_back(d * kDeg);
  }
  return r;
}

std::vector<double> equidistant(int n)
{
  std::vector<double> r;
  for (int k = 0; k < n; ++k)
  {
    r.push_back(k * M_PI / n);
  }
  return r;
}

// Circular difference of two axis directions (radians) modulo π, in degrees.
double dirDiffDeg(double a, double b)
{
  double d = std::fmod(std::abs(a - b), M_PI);
  return std::min(d, M_PI - d) / kDeg;
}

// Closed-form intensity of a homogeneous fiber, the paper's equation (pli-simulation.md §1),
// written here independently of any simulator: I(ρ) = I_T·(1 + sin 2(ρ − φ)·sin δ).
std::vector<double> homogeneousFiber(double iT, double phi, double sinDelta, const std::vector<double>& rho)
{
  std::vector<double> I;
  for (double r : rho)
  {
    I.push_back(iT * (1.0 + std::sin(2.0 * (r - phi)) * sinDelta));
  }
  return I;
}

template <class F>
std::vector<double> sample(F f, const std::vector<double>& rho)
{
  std::vector<double> I;
  for (double r : rho)
  {
    I.push_back(f(r));
  }
  return I;
}

// Bit-identical (NaN == NaN): the thread-count invariance the style guide asks for.
bool sameBits(const std::vector<double>& a, const std::vector<double>& b)
{
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

EpaPixel epa(const std::vector<double>& I, const std::vector<double>& rho)
{
  EpaFit fit;
  const std::string err = fit.init(rho);
  EXPECT_EQ(err, "");
  return fit.pixel(I.data());
}
} // namespace

// the single voxel of pli-simulation S-1.
TEST(PLIAnalysis, EpaSingleVoxelA1)
{
  const std::vector<double> I = { 6500, 10203.645730, 10203.645730, 6500, 2796.354270, 2796.354270 };
  const EpaPixel p = epa(I, anglesDeg({ 0, 30, 60, 90, 120, 150 }));
  EXPECT_NEAR(p.transmittance, 13000.0, 13000.0 * 1e-9);
  EXPECT_LE(dirDiffDeg(p.direction, 0.0), 1e-6);
  EXPECT_NEAR(p.retardation, 0.6579387259, 1e-6);
  EXPECT_GE(p.direction, 0.0);
  EXPECT_LT(p.direction, M_PI);
}

// A-2 first rows: the same sinusoid on equidistant and on irregular angles.
TEST(PLIAnalysis, EpaLeastSquaresOnIrregularAnglesA2)
{
  auto f = [](double r) { return 1.0 + 0.5 * std::sin(2.0 * (r - 30.0 * kDeg)); };
  const std::vector<double> eq = anglesDeg({ 0, 30, 60, 90, 120, 150 });
  const std::vector<double> irr = anglesDeg({ 0, 20, 50, 90, 100, 150 });

  EpaFit fitEq, fitIrr;
  ASSERT_EQ(fitEq.init(eq), "");
  ASSERT_EQ(fitIrr.init(irr), "");
  EXPECT_TRUE(fitEq.equidistant());
  EXPECT_FALSE(fitIrr.equidistant());

  for (const auto* rho : { &eq, &irr })
  {
    const EpaPixel p = epa(sample(f, *rho), *rho);
    EXPECT_NEAR(p.transmittance, 2.0, 1e-12);
    EXPECT_LE(dirDiffDeg(p.direction, 30.0 * kDeg), 1e-10);
    EXPECT_NEAR(p.retardation, 0.5, 1e-12);
  }

  // The equidistant formula misapplied to the irregular angles gives 2.012922 / 28.931213° /
  // 0.554869: check that this trap is real and that we do not fall into it.
  const std::vector<double> I = sample(f, irr);
  Harmonic wrong;
  for (std::size_t k = 0; k < irr.size(); ++k)
  {
    wrong.a0 += I[k] / 6.0;
    wrong.a1 += 2.0 * I[k] * std::sin(2.0 * irr[k]) / 6.0;
    wrong.b1 += 2.0 * I[k] * std::cos(2.0 * irr[k]) / 6.0;
  }
  const EpaPixel w = epaFromHarmonic(wrong);
  EXPECT_NEAR(w.transmittance, 2.012922, 1e-6);
  EXPECT_NEAR(w.direction / kDeg, 28.931213, 1e-6);
  EXPECT_NEAR(w.retardation, 0.554869, 1e-6);
  const EpaPixel p = epa(I, irr);
  EXPECT_GT(std::abs(p.transmittance - w.transmittance), 1e-3);
}

// A-2 remaining rows: known amplitude and phase on 9 equidistant angles (sign convention of §2.3).
TEST(PLIAnalysis, EpaKnownHarmonicsA2)
{
  const std::vector<double> rho = equidistant(9);
  struct Case
  {
    double a0, a1, b1, T, dirDeg, ret;
  };
  const Case cases[] = {
    { 1000, 300, -400, 2000, 26.565051177077990, 0.5 },
    { 1000, -300, 0, 2000, 90, 0.3 },
    { 1000, 0, 400, 2000, 135, 0.4 },
    { 1000, 0, -400, 2000, 45, 0.4 },
    { 100, 150, 0, 200, 0, 1.0 }, // 1.5 clamped
    { 500, 0, 0, 1000, 0, 0 },    // flat: direction 0 by the rule of §2.3
  };
  for (const Case& c : cases)
  {
    const EpaPixel p = epa(sample([&](double r) { return c.a0 + c.a1 * std::sin(2 * r) + c.b1 * std::cos(2 * r); }, rho), rho);
    EXPECT_NEAR(p.transmittance, c.T, c.T * 1e-9);
    EXPECT_LE(dirDiffDeg(p.direction, c.dirDeg * kDeg), 1e-6) << c.a1 << " " << c.b1;
    EXPECT_NEAR(p.retardation, c.ret, 1e-9);
  }
  // Exactly flat data must give exactly 0, not a direction of rounding noise.
  const EpaPixel flat = epa(std::vector<double>(9, 500.0), rho);
  EXPECT_EQ(flat.direction, 0.0);
}

TEST(PLIAnalysis, EpaRefusesAnglesThatDoNotDetermineTheHarmonic)
{
  EpaFit fit;
  EXPECT_NE(fit.init(anglesDeg({ 0, 90 })), "");
  EXPECT_NE(fit.init(anglesDeg({ 0, 90, 180 })), ""); // 3 angles, still 2 distinct values of 2ρ
  EXPECT_NE(fit.init(anglesDeg({ 10 })), "");
  EXPECT_NE(fit.init({}), "");
  const std::string msg = fit.init(anglesDeg({ 0, 90 }));
  EXPECT_NE(msg.find("at least 3"), std::string::npos) << msg;
  EXPECT_NE(fit.init({ 0.0, NAN, 1.0 }), "");
  EXPECT_EQ(fit.init(anglesDeg({ 0, 45, 90 })), ""); // smallest usable set
}

// §2.2: the fast path and the general least squares agree to 1e-12 on equidistant angles.
TEST(PLIAnalysis, EpaFastPathAgreesWithLeastSquares)
{
  const std::vector<double> rho = equidistant(18);
  // The same equidistant set in another order is not "ρ_0 + kπ/N in order": it takes §2.1.
  std::vector<double> shuffled;
  for (int k = 0; k < 18; ++k)
  {
    shuffled.push_back(rho[(k * 5) % 18]);
  }
  EpaFit fast, ls;
  ASSERT_EQ(fast.init(rho), "");
  ASSERT_EQ(ls.init(shuffled), "");
  ASSERT_TRUE(fast.equidistant());
  ASSERT_FALSE(ls.equidistant());
  RandomStream rng(3);
  for (int t = 0; t < 20; ++t)
  {
    const double phi = rng.uniform(0, M_PI), r = rng.uniform(0, 1), iT = rng.uniform(100, 20000);
    const Harmonic a = fast.harmonic(homogeneousFiber(iT, phi, r, rho).data());
    const Harmonic b = ls.harmonic(homogeneousFiber(iT, phi, r, shuffled).data());
    EXPECT_NEAR(a.a0, b.a0, 1e-12 * iT);
    EXPECT_NEAR(a.a1, b.a1, 1e-12 * iT);
    EXPECT_NEAR(a.b1, b.b1, 1e-12 * iT);
    EXPECT_NEAR(a.a0, iT, 1e-12 * iT);
  }
}

// Random fibers through the closed form: EPA recovers T, φ and |sin δ| exactly; with Gaussian
// noise of known size the estimates scatter around the truth with the expected spread.
TEST(PLIAnalysis, EpaRecoversClosedFormFibersWithAndWithoutNoise)
{
  const std::vector<double> rho = anglesDeg({ 0, 17, 41, 66, 90, 123, 151, 170 });
  EpaFit fit;
  ASSERT_EQ(fit.init(rho), "");
  RandomStream rng(11);
  for (int t = 0; t < 50; ++t)
  {
    const double phi = rng.uniform(0, M_PI), r = rng.uniform(0.01, 1), iT = rng.uniform(100, 20000);
    const EpaPixel p = fit.pixel(homogeneousFiber(iT, phi, r, rho).data());
    EXPECT_NEAR(p.transmittance, 2 * iT, 2 * iT * 1e-9);
    EXPECT_LE(dirDiffDeg(p.direction, phi), 1e-6);
    EXPECT_NEAR(p.retardation, r, 1e-9);
  }
  // Noisy: σ = 1 % of I_T per sample; 2000 pixels of (60°, 0.5). The direction error of one pixel
  // is about σ/(I_T·r·√(N/2)) rad = 0.57°; the mean of 2000 must be within 0.1°.
  const double phi = 60 * kDeg, r = 0.5, iT = 1000;
  double sumDir = 0, sumRet = 0, sumT = 0;
  const int n = 2000;
  for (int t = 0; t < n; ++t)
  {
    RandomStream noise(5, t);
    std::vector<double> I = homogeneousFiber(iT, phi, r, rho);
    for (double& v : I)
    {
      v += 0.01 * iT * noise.normal();
    }
    const EpaPixel p = fit.pixel(I.data());
    sumDir += p.direction;
    sumRet += p.retardation;
    sumT += p.transmittance;
  }
  EXPECT_NEAR(sumDir / n / kDeg, 60.0, 0.1);
  EXPECT_NEAR(sumRet / n, 0.5, 0.002);
  EXPECT_NEAR(sumT / n, 2000.0, 1.0);
}

TEST(PLIAnalysis, EpaMapsSubRangeInvalidPixelsAndThreads)
{
  const std::int64_t nx = 7, ny = 5;
  const std::vector<double> rho = equidistant(6);
  std::vector<double> stack;
  for (std::int64_t p = 0; p < nx * ny; ++p)
  {
    const std::vector<double> I = homogeneousFiber(1000 + p, p * 0.1, 0.02 * p, rho);
    stack.insert(stack.end(), I.begin(), I.end());
  }
  stack[3 * 6 + 2] = NAN;                     // pixel 3: non-finite sample
  for (int k = 0; k < 6; ++k) stack[4 * 6 + k] = 0.0; // pixel 4: no light (a0 = 0)

  EpaMaps one, two, part;
  ASSERT_EQ(computeEpa(stack.data(), nx, ny, rho, wholeImage(nx, ny), 1, one), "");
  ASSERT_EQ(computeEpa(stack.data(), nx, ny, rho, wholeImage(nx, ny), 2, two), "");
  EXPECT_TRUE(sameBits(one.direction, two.direction));
  EXPECT_TRUE(sameBits(one.retardation, two.retardation));
  EXPECT_TRUE(sameBits(one.transmittance, two.transmittance));
  for (int p : { 3, 4 })
  {
    EXPECT_TRUE(std::isnan(one.transmittance[p]));
    EXPECT_TRUE(std::isnan(one.direction[p]));
    EXPECT_TRUE(std::isnan(one.retardation[p]));
  }
  EXPECT_NEAR(one.transmittance[10], 2 * 1010.0, 1e-9);
  EXPECT_NEAR(one.retardation[10], 0.2, 1e-12);

  const PixelRange r{ 2, 5, 1, 4 };
  ASSERT_EQ(computeEpa(stack.data(), nx, ny, rho, r, 2, part), "");
  for (std::int64_t j = 0; j < ny; ++j)
  {
    for (std::int64_t i = 0; i < nx; ++i)
    {
      const std::int64_t p = i + nx * j;
      const bool inside = i >= 2 && i < 5 && j >= 1 && j < 4;
      if (inside)
      {
        EXPECT_EQ(part.direction[p], one.direction[p]);
      }
      else
      {
        EXPECT_TRUE(std::isnan(part.direction[p]));
      }
    }
  }
  EXPECT_NE(computeEpa(stack.data(), nx, ny, rho, PixelRange{ 0, 8, 0, 5 }, 1, part), "");
  // Cancellation is reported, not ignored.
  EXPECT_EQ(computeEpa(stack.data(), nx, ny, rho, wholeImage(nx, ny), 1, part, [](double) { return false; }),
    "cancelled");
}

// inclination from retardation with r_ref = 0.6579387259 (t_rel 0.4571428571).
TEST(PLIAnalysis, InclinationFromRetardationA3)
{
  const double rRef = 0.6579387259;
  for (double aDeg : { 0.0, 20.0, 45.0, 60.0, 89.0, 90.0 })
  {
    const double c = std::cos(aDeg * kDeg);
    const double r = std::abs(std::sin(0.7180783208 * c * c));
    EXPECT_NEAR(inclinationFromRetardation(r, rRef) / kDeg, aDeg, 1e-6) << aDeg;
  }
  EXPECT_NEAR(inclinationFromRetardation(0.351375, rRef) / kDeg, 45.0, 1e-3);
  EXPECT_NEAR(inclinationFromRetardation(0.592436, rRef) / kDeg, 20.0, 1e-3);
  EXPECT_EQ(inclinationFromRetardation(rRef, rRef), 0.0);
  EXPECT_EQ(inclinationFromRetardation(0.7, rRef), 0.0);
  EXPECT_EQ(inclinationFromRetardation(0.0, rRef), M_PI / 2);
  EXPECT_TRUE(std::isnan(inclinationFromRetardation(NAN, rRef)));
}

TEST(PLIAnalysis, InclinationMapAutomaticReference)
{
  // Row of fibers at inclinations 0°, 20°, 45°, 90° plus a NaN pixel: the automatic reference is
  // the in-plane pixel's retardation, so the map returns the inclinations themselves.
  const double incl[] = { 0, 20, 45, 90 };
  std::vector<double> ret;
  for (double a : incl)
  {
    const double c = std::cos(a * kDeg);
    ret.push_back(std::abs(std::sin(0.7180783208 * c * c)));
  }
  ret.push_back(NAN);
  std::vector<double> out;
  ASSERT_EQ(inclinationMapFromRetardation(ret.data(), 5, 1, wholeImage(5, 1), 0.0, 2, out), "");
  EXPECT_NEAR(maxRetardation(ret.data(), 5, wholeImage(5, 1)), 0.6579387259, 1e-9);
  for (int k = 0; k < 4; ++k)
  {
    EXPECT_NEAR(out[k] / kDeg, incl[k], 1e-6);
  }
  EXPECT_TRUE(std::isnan(out[4]));
  // Explicit reference larger than every r: the in-plane pixel is now inclined.
  ASSERT_EQ(inclinationMapFromRetardation(ret.data(), 5, 1, wholeImage(5, 1), 0.9, 1, out), "");
  EXPECT_GT(out[0] / kDeg, 10.0);
  const std::string err = inclinationMapFromRetardation(ret.data(), 5, 1, wholeImage(5, 1), 1.5, 1, out);
  EXPECT_NE(err.find("ReferenceRetardation"), std::string::npos) << err;
  // All-zero retardation (automatic r_ref = 0): every pixel is vertical, no division by zero.
  std::vector<double> zero(3, 0.0);
  ASSERT_EQ(inclinationMapFromRetardation(zero.data(), 3, 1, wholeImage(3, 1), 0.0, 1, out), "");
  EXPECT_EQ(out[1], M_PI / 2);
}
