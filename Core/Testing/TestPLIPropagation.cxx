// Müller propagation against the closed form and the test vectors S-1 … S-5 of
// docs/pli-simulation.md §8 (single, stacked and tilted 60 µm voxels built from real fibers).
#include "PLI/Simulator.h"
#include "PLI/TissueSpec.h"
#include "PLITestUtil.h"

#include <gtest/gtest.h>

using namespace fiberpli;
using namespace fiberpli::pli;
using namespace plitest;

namespace
{
constexpr double kI0 = 26000.0;
constexpr double kTolI = 1e-6 * kI0;

SimParams params(int N = 6)
{
  SimParams p;
  for (int k = 0; k < N; ++k)
    p.rho.push_back(k * M_PI / N);
  p.threads = 1;
  return p;
}

SectionLattice voxels(std::int64_t nz, double voxel = 60.0)
{
  SectionLattice l;
  l.voxel = voxel;
  l.n[0] = 1;
  l.n[1] = 1;
  l.n[2] = nz;
  return l;
}

TissueSpec oneLayer(double dn, double mu, AxisModel m = AxisModel::Parallel)
{
  TissueSpec s;
  s.bundleIds = { 0 };
  s.layers = { { Layer{ 1.0, dn, mu, m } } };
  return s;
}

// Intensities of the single 60 µm voxel whose fiber runs along u.
std::vector<double> singleVoxel(const Vec3& u, double dn, double mu, SimParams p, View view = {})
{
  FiberModel m;
  m.fibers.push_back(line({ 30, 30, 30 }, u, 1e4, 1e4));
  std::vector<Stack> out;
  SimResult r = simulate(m, oneLayer(dn, mu), voxels(1), p, { view }, GridRange{ 0, 1, 0, 1 }, out);
  EXPECT_TRUE(r.status.ok()) << r.status.error;
  EXPECT_FALSE(r.emptySection);
  return std::vector<double>(out[0].data.begin(), out[0].data.end());
}

void expectIntensities(const std::vector<double>& I, const std::vector<double>& expected)
{
  ASSERT_EQ(I.size(), expected.size());
  for (std::size_t k = 0; k < I.size(); ++k)
    EXPECT_NEAR(I[k], expected[k], kTolI) << "rotation " << k;
}
} // namespace

TEST(PLIPropagation, S1SingleVoxelReferenceCase)
{
  const std::vector<double> I = singleVoxel({ 1, 0, 0 }, -0.001, 0, params());
  expectIntensities(I, { 6500, 10203.645730, 10203.645730, 6500, 2796.354270, 2796.354270 });
  const Epa e = epa(I.data(), 6);
  EXPECT_NEAR(e.T, 13000, 13000 * 1e-9);
  EXPECT_LT(dirDiff(e.dirDeg, 0), 1e-4);
  EXPECT_NEAR(e.ret, 0.657939, 1e-6);
  EXPECT_NEAR(e.ret, std::fabs(std::sin(-0.7180783208)), 1e-9);
}

TEST(PLIPropagation, S2Variants)
{
  expectIntensities(singleVoxel(dirVec(30, 0), -0.001, 0, params()),
    { 2796.354270, 6500, 10203.645730, 10203.645730, 6500, 2796.354270 });
  {
    const std::vector<double> I = singleVoxel(dirVec(30, 0), 0.001, 0, params());
    const Epa e = epa(I.data(), 6);
    EXPECT_LT(dirDiff(e.dirDeg, 120), 1e-4);
    EXPECT_NEAR(e.ret, 0.657939, 1e-6);
  }
  expectIntensities(singleVoxel(dirVec(0, 45), -0.001, 0, params()),
    { 6500, 8477.946905, 8477.946905, 6500, 4522.053095, 4522.053095 });
  {
    const std::vector<double> I = singleVoxel(dirVec(60, 20), -0.002, 0, params());
    expectIntensities(I, { 1126.660423, 1126.660423, 6500, 11873.339577, 11873.339577, 6500 });
    const Epa e = epa(I.data(), 6);
    EXPECT_LT(dirDiff(e.dirDeg, 60), 1e-4);
    EXPECT_NEAR(e.ret, 0.954554, 1e-6);
  }
  {
    const std::vector<double> I = singleVoxel({ 1, 0, 0 }, -0.001, 5, params());
    const std::vector<double> ref = { 6500, 10203.645730, 10203.645730, 6500, 2796.354270,
      2796.354270 };
    for (int k = 0; k < 6; ++k)
      EXPECT_NEAR(I[k], ref[k] * 0.7408182207, kTolI);
    EXPECT_NEAR(epa(I.data(), 6).T, 9630.636869, 9630.636869 * 1e-9);
  }
  for (int N : { 9, 18 })
  {
    const std::vector<double> I = singleVoxel({ 1, 0, 0 }, -0.001, 0, params(N));
    const Epa e = epa(I.data(), N);
    EXPECT_NEAR(e.T, 13000, 13000 * 1e-9);
    EXPECT_LT(dirDiff(e.dirDeg, 0), 1e-4);
    EXPECT_NEAR(e.ret, 0.657939, 1e-6);
  }
  expectIntensities(
    singleVoxel({ 0, 0, 1 }, -0.001, 0, params()), { 6500, 6500, 6500, 6500, 6500, 6500 });
}

TEST(PLIPropagation, S3StepRule)
{
  for (double h : { 1.0, 0.5, 0.3, 2.0 })
  {
    SimParams p = params();
    p.step = h;
    const std::vector<double> I = singleVoxel({ 1, 0, 0 }, -0.001, 0, p);
    EXPECT_NEAR(epa(I.data(), 6).ret, 0.657939, 1e-6) << "ExactLength h " << h;
  }
  const std::pair<double, double> midpoint[] = { { 1.0, 0.657939 }, { 0.5, 0.657939 },
    { 0.3, 0.602213 }, { 2.0, 0.0 } };
  for (const auto& hr : midpoint)
  {
    SimParams p = params();
    p.step = hr.first;
    p.stepRule = StepRule::FastPLIMidpoint;
    const std::vector<double> I = singleVoxel({ 1, 0, 0 }, -0.001, 0, p);
    EXPECT_NEAR(epa(I.data(), 6).ret, hr.second, 1e-6) << "FastPLIMidpoint h " << hr.first;
  }
}

TEST(PLIPropagation, S4StackedVoxelsFixTheHandedness)
{
  struct Row
  {
    double bottom, top, dir, ret;
  };
  const Row rows[] = { { 0, 0, 0, 0.990950 }, { 0, 90, -1, 0 }, { 0, 45, 18.491180, 0.823637 },
    { 45, 0, 26.508820, 0.823637 } };
  for (const Row& row : rows)
  {
    FiberModel m;
    m.fibers.push_back(line({ 30, 30, 30 }, dirVec(row.bottom, 0), 1e3, 40));
    m.fibers.push_back(line({ 30, 30, 90 }, dirVec(row.top, 0), 1e3, 40));
    std::vector<Stack> out;
    SimResult r = simulate(
      m, oneLayer(-0.001, 0), voxels(2), params(), { View{} }, GridRange{ 0, 1, 0, 1 }, out);
    ASSERT_TRUE(r.status.ok()) << r.status.error;
    const Epa e = epa(out[0].data.data(), 6);
    EXPECT_NEAR(e.T, 13000, 13000 * 1e-9);
    EXPECT_NEAR(e.ret, row.ret, 1e-6) << row.bottom << "/" << row.top;
    if (row.dir >= 0)
    {
      EXPECT_LT(dirDiff(e.dirDeg, row.dir), 1e-4) << row.bottom << "/" << row.top;
    }
    if (row.bottom == 0 && row.top == 45)
      expectIntensities(out[0].data,
        { 3279.413274, 8593.352367, 11813.939093, 9720.586726, 4406.647633, 1186.060907 });
  }
}

TEST(PLIPropagation, S5TiltedSingleVoxelBothConventions)
{
  struct Row
  {
    double az, dirPhys, retPhys, dirFast, retFast;
  };
  const Row rows[] = { { 0, 0, 0.237591, 0, 0.469982 }, { 180, 0, 0.469982, 0, 0.237591 },
    { 90, 170.1489, 0.366804, 9.8511, 0.366804 }, { 270, 9.8511, 0.366804, 170.1489, 0.366804 } };
  const double th = 10.0 * M_PI / 180.0;
  for (const Row& row : rows)
    for (int conv = 0; conv < 2; ++conv)
    {
      SimParams p = params();
      p.step = 1.0 / std::cos(th);
      p.conv = conv == 0 ? TiltConvention::Physical : TiltConvention::FastPLI;
      const std::vector<double> I =
        singleVoxel(dirVec(0, 45), -0.001, 0, p, View{ th, row.az * M_PI / 180 });
      const Epa e = epa(I.data(), 6);
      EXPECT_NEAR(e.ret, conv == 0 ? row.retPhys : row.retFast, 1e-6)
        << "azimuth " << row.az << " conv " << conv;
      EXPECT_LT(dirDiff(e.dirDeg, conv == 0 ? row.dirPhys : row.dirFast), 1e-4)
        << "azimuth " << row.az;
      EXPECT_NEAR(e.T, 13000, 13000 * 1e-9);
    }
}

TEST(PLIPropagation, ZeroBirefringenceAndAbsorptionOnly)
{
  // Δn = 0: no modulation, only Beer–Lambert over 60 µm at μ = 2/mm.
  const std::vector<double> I = singleVoxel(dirVec(33, 12), 0.0, 2.0, params());
  for (double v : I)
    EXPECT_NEAR(v, 6500 * std::exp(-2.0 * 0.06), kTolI);
}
