// PLI analysis (docs/pli-analysis.md §2, §3; test vectors A-1 … A-5): EPA on equidistant and
// arbitrary polarizer angles, inclination from retardation, and the tilt fit on closed-form views.
#include "Analysis/Axis.h"
#include "Analysis/Epa.h"
#include "Analysis/PliAnalysis.h"
#include "Analysis/RetardationInclination.h"
#include "Analysis/TiltFit.h"

#include "Util/Random.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
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

// Closed-form intensity of a homogeneous fiber, the paper's equation (docs/pli-simulation.md §1),
// written here independently of any simulator: I(ρ) = I_T·(1 + sin 2(ρ − φ)·sin δ).
std::vector<double> homogeneousFiber(
  double iT, double phi, double sinDelta, const std::vector<double>& rho)
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

// the single voxel of docs/pli-simulation.md §8 S-1.
TEST(PLIAnalysis, EpaSingleVoxelA1)
{
  const std::vector<double> I = { 6500, 10203.645730, 10203.645730, 6500, 2796.354270,
    2796.354270 };
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

// A-2 remaining rows: known amplitude and phase on 9 equidistant angles (sign convention of
// docs/pli-analysis.md §2.3).
TEST(PLIAnalysis, EpaKnownHarmonicsA2)
{
  const std::vector<double> rho = equidistant(9);
  struct Case
  {
    double a0, a1, b1, T, dirDeg, ret;
  };
  const Case cases[] = {
    { 1000, 300, -400, 2000, 26.565051177077990, 0.5 }, { 1000, -300, 0, 2000, 90, 0.3 },
    { 1000, 0, 400, 2000, 135, 0.4 }, { 1000, 0, -400, 2000, 45, 0.4 },
    { 100, 150, 0, 200, 0, 1.0 }, // 1.5 clamped
    { 500, 0, 0, 1000, 0, 0 },    // flat: direction 0 by the rule of docs/pli-analysis.md §2.3
  };
  for (const Case& c : cases)
  {
    const EpaPixel p = epa(
      sample([&](double r) { return c.a0 + c.a1 * std::sin(2 * r) + c.b1 * std::cos(2 * r); }, rho),
      rho);
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
  stack[3 * 6 + 2] = NAN; // pixel 3: non-finite sample
  for (int k = 0; k < 6; ++k)
    stack[4 * 6 + k] = 0.0; // pixel 4: no light (a0 = 0)

  EpaMaps one, two, part;
  ASSERT_EQ(computeEpa(stack.data(), nx, ny, rho, wholeImage(nx, ny), 1, one).error, "");
  ASSERT_EQ(computeEpa(stack.data(), nx, ny, rho, wholeImage(nx, ny), 2, two).error, "");
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

  const GridRange r{ 2, 5, 1, 4 };
  ASSERT_EQ(computeEpa(stack.data(), nx, ny, rho, r, 2, part).error, "");
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
  EXPECT_NE(computeEpa(stack.data(), nx, ny, rho, GridRange{ 0, 8, 0, 5 }, 1, part).error, "");
  // Cancellation is reported, not ignored.
  EXPECT_TRUE(computeEpa(stack.data(), nx, ny, rho, wholeImage(nx, ny), 1, part,
    [](double) {
      return false;
    }).aborted);
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
  const std::string err =
    inclinationMapFromRetardation(ret.data(), 5, 1, wholeImage(5, 1), 1.5, 1, out);
  EXPECT_NE(err.find("ReferenceRetardation"), std::string::npos) << err;
  // All-zero retardation (automatic r_ref = 0): every pixel is vertical, no division by zero.
  std::vector<double> zero(3, 0.0);
  ASSERT_EQ(inclinationMapFromRetardation(zero.data(), 3, 1, wholeImage(3, 1), 0.0, 1, out), "");
  EXPECT_EQ(out[1], M_PI / 2);
}

// ---- Tilt fit (§3.2) --------------------------------------------------------------------------
namespace
{
// Rotation of v by angle a about the unit axis u (Rodrigues), independent of TiltFit's matrices.
Vec3 rotate(const Vec3& v, const Vec3& u, double a)
{
  return std::cos(a) * v + std::sin(a) * cross(u, v) + (1.0 - std::cos(a)) * dot(u, v) * u;
}

struct Column
{
  double dirDeg, inclDeg;
  double dn = -0.001, thickness = 60.0, lambdaNm = 525.0, i0 = 26000.0;
};

// Closed-form intensities of a uniform column in view j (0 flat; 1..4 tilt azimuths 0°, 90°,
// 180°, 270°) by tilting the specimen by tau (in tissue) about u = (−sin ψ, cos ψ, 0): the
// beam sees the axis rotated by −tau (Physical: v_b = Rᵀv) or +tau (FastPLI: R·v), along a path
// d/cos tau. I = (I0/4)(1 − sin δ · sin 2(ρ − φ_b)), δ = 2π·Δn·path·cos²α_b/λ
// (docs/pli-simulation.md §4.2).
std::vector<double> columnView(
  const Column& c, int j, double tau, bool physical, const std::vector<double>& rho)
{
  Vec3 v{ std::cos(c.inclDeg * kDeg) * std::cos(c.dirDeg * kDeg),
    std::cos(c.inclDeg * kDeg) * std::sin(c.dirDeg * kDeg), std::sin(c.inclDeg * kDeg) };
  double path = c.thickness;
  if (j > 0)
  {
    const double psi = (j - 1) * M_PI / 2;
    const Vec3 u{ -std::sin(psi), std::cos(psi), 0.0 };
    v = rotate(v, u, physical ? -tau : tau);
    path /= std::cos(tau);
  }
  const double cos2 = v.x * v.x + v.y * v.y;
  const double phiB = std::atan2(v.y, v.x);
  const double delta = 2 * M_PI * c.dn * path * 1e-6 * cos2 / (c.lambdaNm * 1e-9);
  std::vector<double> I;
  for (double r : rho)
  {
    I.push_back(c.i0 / 4 * (1 - std::sin(delta) * std::sin(2 * (r - phiB))));
  }
  return I;
}

struct Views
{
  std::vector<double> v[5];
  std::vector<const double*> ptr() const
  {
    return { v[0].data(), v[1].data(), v[2].data(), v[3].data(), v[4].data() };
  }
};

Views columnViews(const Column& c, double tau, bool physical, const std::vector<double>& rho)
{
  Views out;
  for (int j = 0; j < 5; ++j)
  {
    out.v[j] = columnView(c, j, tau, physical, rho);
  }
  return out;
}

double axisError(double dirA, double inclA, double dirB, double inclB)
{
  return norm(cross(axisFromAngles(dirA, inclA), axisFromAngles(dirB, inclB)));
}

TiltFit makeFit(const std::vector<double>& rho, double tauDeg, TiltConvention conv, double gain)
{
  TiltFit fit;
  TiltFitOptions o;
  o.views = fourTiltViews(tauDeg * kDeg);
  o.convention = conv;
  o.gain = gain;
  EXPECT_EQ(fit.init(rho, o), "");
  return fit;
}
} // namespace

// A-4 table: per-view EPA of the closed-form views (this validates the test's own view model
// against the notes), then the fit under both conventions, and the wrong convention is caught.
TEST(PLIAnalysis, TiltFitClosedFormViewsA4)
{
  const std::vector<double> rho = equidistant(18);
  struct Row
  {
    double dir, incl;
    double viewDir[5], viewRet[5];
  };
  const Row rows[] = {
    { 30, 20, { 30.0, 31.1522, 28.1205, 29.1380, 31.5904 },
      { 0.592436, 0.560579, 0.576308, 0.622326, 0.611887 } },
    { 120, -60, { 120.0, 110.9569, 115.9364, 127.4660, 125.6920 },
      { 0.178557, 0.154483, 0.233520, 0.213062, 0.132072 } },
    { 0, 45, { 0.0, 0.0, 174.5252, 0.0, 5.4748 },
      { 0.351375, 0.287748, 0.356027, 0.416439, 0.356027 } },
  };
  EpaFit epaFit;
  ASSERT_EQ(epaFit.init(rho), "");
  const int fastOrder[5] = { 0, 3, 4, 1, 2 }; // FastPLI swaps 0°↔180° and 90°↔270°
  for (const Row& row : rows)
  {
    const Column col{ row.dir, row.incl };
    for (bool physical : { true, false })
    {
      const Views views = columnViews(col, 5.5 * kDeg, physical, rho);
      for (int j = 0; j < 5; ++j)
      {
        const int e = physical ? j : fastOrder[j];
        const EpaPixel p = epaFit.pixel(views.v[j].data());
        EXPECT_NEAR(p.transmittance, 13000.0, 13000.0 * 1e-9);
        EXPECT_LE(dirDiffDeg(p.direction, row.viewDir[e] * kDeg), 1e-4) << row.dir << " view " << j;
        EXPECT_NEAR(p.retardation, row.viewRet[e], 1e-6) << row.dir << " view " << j;
      }
      const TiltFit fit =
        makeFit(rho, 5.5, physical ? TiltConvention::Physical : TiltConvention::FastPLI, 1.0);
      const TiltFitResult f = fit.pixel(views.ptr());
      EXPECT_LE(axisError(f.direction, f.inclinationSigned, row.dir * kDeg, row.incl * kDeg), 1e-6)
        << row.dir << "," << row.incl << " got " << f.direction / kDeg << ","
        << f.inclinationSigned / kDeg;
      EXPECT_NEAR(f.relativeThickness, 0.4571428571, 0.4571428571 * 1e-8);
      EXPECT_LT(f.chi2, 1e-20);
      EXPECT_NEAR(f.inclination, std::abs(f.inclinationSigned), 0.0);
      EXPECT_GE(f.direction, 0.0);
      EXPECT_LT(f.direction, M_PI);
    }
  }
  // The data of row 1 (Physical) fitted as if FastPLI: the sign of the inclination flips.
  const Views views = columnViews(Column{ 30, 20 }, 5.5 * kDeg, true, rho);
  const TiltFitResult wrong = makeFit(rho, 5.5, TiltConvention::FastPLI, 1.0).pixel(views.ptr());
  EXPECT_LE(axisError(wrong.direction, wrong.inclinationSigned, 30 * kDeg, -20 * kDeg), 1e-6);
  EXPECT_GT(axisError(wrong.direction, wrong.inclinationSigned, 30 * kDeg, 20 * kDeg), 0.5);
}

// fastPLI's ROFL test case, N = 6.
TEST(PLIAnalysis, TiltFitFastPliRoflCaseA5)
{
  const std::vector<double> rho = equidistant(6);
  const Column col{ 0, 45 };
  const std::vector<double> flat = columnView(col, 0, 5.5 * kDeg, false, rho);
  const double row[6] = { 6500, 8477.946905, 8477.946905, 6500, 4522.053095, 4522.053095 };
  for (int k = 0; k < 6; ++k)
  {
    EXPECT_NEAR(flat[k], row[k], 1e-6);
  }
  for (TiltConvention conv : { TiltConvention::FastPLI, TiltConvention::Physical })
  {
    const Views views = columnViews(col, 5.5 * kDeg, conv == TiltConvention::Physical, rho);
    const TiltFitResult f = makeFit(rho, 5.5, conv, 1.0).pixel(views.ptr());
    EXPECT_LE(axisError(f.direction, f.inclinationSigned, 0.0, 45 * kDeg), 1e-6)
      << f.direction / kDeg << " " << f.inclinationSigned / kDeg << " t " << f.relativeThickness
      << " chi2 " << f.chi2 << " it " << f.iterations;
    // fastPLI reports (180°, −45°): the same axis.
    EXPECT_LE(axisError(f.direction, f.inclinationSigned, M_PI, -45 * kDeg), 1e-6);
    EXPECT_NEAR(f.relativeThickness, 0.4571428571, 1e-8);
    EXPECT_NEAR(f.inclination / kDeg, 45.0, 1e-4);
  }
}

// Random axes over the whole sphere and thicknesses with t_rel < 1: the fit recovers each one.
TEST(PLIAnalysis, TiltFitRecoversRandomAxes)
{
  const std::vector<double> rho = equidistant(9);
  const TiltFit fit = makeFit(rho, 8.0, TiltConvention::Physical, 1.0);
  RandomStream rng(17);
  int checked = 0;
  for (int t = 0; t < 30; ++t)
  {
    Column col{ rng.uniform(0, 180), rng.uniform(-75, 75) };
    col.dn = -rng.uniform(0.0004, 0.0018); // t_rel 0.18 … 0.82
    const double tRel = 4 * col.thickness * std::abs(col.dn) / (col.lambdaNm * 1e-3);
    const TiltFitResult f = fit.pixel(columnViews(col, 8.0 * kDeg, true, rho).ptr());
    EXPECT_LE(
      axisError(f.direction, f.inclinationSigned, col.dirDeg * kDeg, col.inclDeg * kDeg), 1e-6)
      << col.dirDeg << "," << col.inclDeg << " t " << tRel << " got " << f.direction / kDeg << ","
      << f.inclinationSigned / kDeg << " t " << f.relativeThickness;
    EXPECT_NEAR(f.relativeThickness, tRel, 1e-7 * tRel);
    ++checked;
  }
  EXPECT_EQ(checked, 30);
}

// Noisy views (Gaussian approximation of the camera model, Var = g·I, g = 3) of the S-6 fiber:
// the fit is unbiased within the A-8 tolerances over 100 pixels.
TEST(PLIAnalysis, TiltFitNoisyViewsStatistics)
{
  const std::vector<double> rho = equidistant(18);
  const TiltFit fit = makeFit(rho, 5.5, TiltConvention::Physical, 3.0);
  const Views clean = columnViews(Column{ 30, 20 }, 5.5 * kDeg, true, rho);
  double sDir = 0, sIncl = 0, sT = 0, sDir2 = 0;
  const int n = 100;
  for (int p = 0; p < n; ++p)
  {
    Views v = clean;
    for (int j = 0; j < 5; ++j)
    {
      RandomStream noise(2024, p, j);
      for (double& x : v.v[j])
      {
        x += std::sqrt(3.0 * x) * noise.normal();
      }
    }
    const TiltFitResult f = fit.pixel(v.ptr());
    // Unwrap the direction near 30° and take the sign-consistent inclination of the canonical axis.
    const double d = f.direction / kDeg;
    sDir += d;
    sDir2 += (d - 30) * (d - 30);
    sIncl += f.inclinationSigned / kDeg;
    sT += f.relativeThickness;
  }
  EXPECT_NEAR(sDir / n, 30.0, 0.1);
  EXPECT_NEAR(sIncl / n, 20.0, 1.0);
  EXPECT_NEAR(sT / n, 0.457, 0.01);
  EXPECT_LT(std::sqrt(sDir2 / n), 0.5); // A-8 Monte Carlo: sd ≈ 0.15°
}

TEST(PLIAnalysis, TiltFitErrorsMapsAndThreads)
{
  TiltFit fit;
  TiltFitOptions o;
  o.views = fourTiltViews(5.5 * kDeg);
  EXPECT_NE(fit.init(equidistant(3), o), ""); // needs N >= 4
  o.views = fourTiltViews(0.0);
  const std::string err = fit.init(equidistant(6), o);
  EXPECT_NE(err.find("tilt_angle"), std::string::npos) << err;

  // A 6 × 4 image of different fibers; pixel 5 has no light in tilt 2.
  const std::int64_t nx = 6, ny = 4;
  const std::vector<double> rho = equidistant(8);
  std::vector<double> stacks[5];
  for (std::int64_t p = 0; p < nx * ny; ++p)
  {
    const Views v = columnViews(Column{ 7.0 * p, -70.0 + 6.0 * p }, 6 * kDeg, true, rho);
    for (int j = 0; j < 5; ++j)
    {
      stacks[j].insert(stacks[j].end(), v.v[j].begin(), v.v[j].end());
    }
  }
  for (int k = 0; k < 8; ++k)
  {
    stacks[3][5 * 8 + k] = 0.0;
  }
  o.views = fourTiltViews(6 * kDeg);
  o.gain = 0.0; // noise-free → 1
  const std::vector<const double*> tilts{ stacks[1].data(), stacks[2].data(), stacks[3].data(),
    stacks[4].data() };
  TiltMaps one, two;
  ASSERT_EQ(
    computeTiltFit(stacks[0].data(), tilts, nx, ny, rho, o, wholeImage(nx, ny), 1, one).error, "");
  ASSERT_EQ(
    computeTiltFit(stacks[0].data(), tilts, nx, ny, rho, o, wholeImage(nx, ny), 2, two).error, "");
  EXPECT_TRUE(sameBits(one.direction, two.direction));
  EXPECT_TRUE(sameBits(one.inclinationSigned, two.inclinationSigned));
  EXPECT_TRUE(sameBits(one.relativeThickness, two.relativeThickness));
  EXPECT_TRUE(sameBits(one.chi2, two.chi2));
  for (std::int64_t p = 0; p < nx * ny; ++p)
  {
    if (p == 5)
    {
      EXPECT_TRUE(std::isnan(one.direction[p]));
      EXPECT_TRUE(std::isnan(one.chi2[p]));
      continue;
    }
    EXPECT_LE(axisError(one.direction[p], one.inclinationSigned[p], 7.0 * p * kDeg,
                (-70.0 + 6.0 * p) * kDeg),
      1e-6)
      << p;
  }
  const std::vector<const double*> missing{ stacks[1].data(), nullptr, stacks[3].data(),
    stacks[4].data() };
  const std::string e2 =
    computeTiltFit(stacks[0].data(), missing, nx, ny, rho, o, wholeImage(nx, ny), 1, two).error;
  EXPECT_NE(e2.find("intensity_tilt_1"), std::string::npos) << e2;
}

// The whole PLIAnalysis computation on the closed-form S-6 column (Core part of A-8): Auto picks
// the tilt fit when the tilts exist; the Retardation method with r_ref 0.6579387259 gives 20°.
TEST(PLIAnalysis, DriverOnUniformSlabA8Core)
{
  const std::int64_t nx = 3, ny = 2;
  const std::vector<double> rho = equidistant(18);
  const Views v = columnViews(Column{ 30, 20 }, 5.5 * kDeg, true, rho);
  std::vector<double> stacks[5];
  for (std::int64_t p = 0; p < nx * ny; ++p)
  {
    for (int j = 0; j < 5; ++j)
    {
      stacks[j].insert(stacks[j].end(), v.v[j].begin(), v.v[j].end());
    }
  }
  PliStack s;
  s.intensity = stacks[0].data();
  s.tilts = { stacks[1].data(), stacks[2].data(), stacks[3].data(), stacks[4].data() };
  s.nx = nx;
  s.ny = ny;
  s.rho = rho;
  s.tiltViews = fourTiltViews(5.5 * kDeg);
  s.noiseGain = 0.0; // noise-free simulation → weights with g = 1

  PliAnalysisOptions o;
  PliAnalysisMaps m;
  std::vector<double> fractions;
  ASSERT_EQ(analysePli(s, o, wholeImage(nx, ny), m,
              [&](double f)
              {
                fractions.push_back(f);
                return true;
              })
              .error,
    "");
  EXPECT_EQ(m.method, InclinationMethod::Tilt);
  ASSERT_FALSE(fractions.empty());
  EXPECT_EQ(fractions.back(), 1.0);
  for (std::size_t p = 0; p < 6; ++p)
  {
    EXPECT_LE(dirDiffDeg(m.direction[p], 30 * kDeg), 1e-4);
    EXPECT_NEAR(m.inclination[p] / kDeg, 20.0, 1e-4);
    EXPECT_NEAR(m.inclinationSigned[p] / kDeg, 20.0, 1e-4);
    EXPECT_NEAR(m.relativeThickness[p], 0.4571428571, 1e-6);
    EXPECT_NEAR(m.retardation[p], 0.592436, 1e-6);
    EXPECT_NEAR(m.transmittance[p], 13000.0, 13000.0 * 1e-6);
    EXPECT_LT(m.chi2[p], 1e-20);
  }

  o.method = InclinationMethod::Retardation;
  o.referenceRetardation = 0.6579387259;
  ASSERT_EQ(analysePli(s, o, wholeImage(nx, ny), m).error, "");
  EXPECT_EQ(m.method, InclinationMethod::Retardation);
  EXPECT_TRUE(m.inclinationSigned.empty());
  for (std::size_t p = 0; p < 6; ++p)
  {
    EXPECT_NEAR(m.inclination[p] / kDeg, 20.0, 1e-4);
  }

  // Automatic reference with a "global" maximum supplied by the caller (MPI AllReduce stand-in).
  o.referenceRetardation = 0.0;
  int calls = 0;
  o.globalMaxRetardation = [&](double local)
  {
    ++calls;
    EXPECT_NEAR(local, 0.592436, 1e-6);
    return 0.6579387259;
  };
  ASSERT_EQ(analysePli(s, o, wholeImage(nx, ny), m).error, "");
  EXPECT_EQ(calls, 1);
  EXPECT_NEAR(m.inclination[0] / kDeg, 20.0, 1e-4);

  // Auto without tilts → Retardation; Tilt without tilts → an error naming the missing array.
  PliStack flat = s;
  flat.tilts[2] = nullptr;
  PliAnalysisOptions a;
  ASSERT_EQ(analysePli(flat, a, wholeImage(nx, ny), m).error, "");
  EXPECT_EQ(m.method, InclinationMethod::Retardation);
  EXPECT_NEAR(m.inclination[0], 0.0, 0.0); // automatic r_ref = the uniform retardation
  a.method = InclinationMethod::Tilt;
  const std::string err = analysePli(flat, a, wholeImage(nx, ny), m).error;
  EXPECT_NE(err.find("intensity_tilt_2"), std::string::npos) << err;
  flat.tilts = s.tilts;
  flat.tiltViews = fourTiltViews(0.0);
  EXPECT_NE(analysePli(flat, a, wholeImage(nx, ny), m).error.find("tilt_angle"), std::string::npos);
  flat.rho = anglesDeg({ 0, 90 });
  EXPECT_NE(analysePli(flat, PliAnalysisOptions{}, wholeImage(nx, ny), m).error, "");
}

TEST(PLIAnalysis, OptionsOutsideTheirRangesAreNamed)
{
  InclinationMethod method = InclinationMethod::Auto;
  for (int bad : { -1, 3, 1000 })
  {
    EXPECT_EQ(inclinationMethodFromCode(bad, method),
      "InclinationMethod is " + std::to_string(bad) +
        ", must be 0 (Auto), 1 (Retardation) or 2 (Tilt)");
    EXPECT_EQ(method, InclinationMethod::Auto);
  }
  EXPECT_EQ(inclinationMethodFromCode(2, method), "");
  EXPECT_EQ(method, InclinationMethod::Tilt);

  PliAnalysisOptions o;
  EXPECT_EQ(checkPliAnalysisOptions(o), ""); // the defaults: automatic r_ref, gain from the data
  for (double bad : { -0.25, 1.5, std::nan("") })
  {
    o.referenceRetardation = bad;
    EXPECT_NE(checkPliAnalysisOptions(o).find("ReferenceRetardation is "), std::string::npos)
      << bad;
  }
  o.referenceRetardation = 1.0;
  EXPECT_EQ(checkPliAnalysisOptions(o), "");
  for (double bad : { -0.5, -2.0, 2e6, std::nan("") })
  {
    o.noiseGain = bad;
    EXPECT_NE(checkPliAnalysisOptions(o).find("NoiseGain is "), std::string::npos) << bad;
  }
  for (double good : { -1.0, 0.0, 3.0, kMaxAnalysisNoiseGain })
  {
    o.noiseGain = good;
    EXPECT_EQ(checkPliAnalysisOptions(o), "") << good;
  }
  // analysePli refuses them too, before touching the stack.
  o.noiseGain = -0.5;
  PliStack stack;
  PliAnalysisMaps maps;
  EXPECT_NE(analysePli(stack, o, GridRange{ 0, 0, 0, 0 }, maps).error.find("NoiseGain is -0.5"),
    std::string::npos);
}
