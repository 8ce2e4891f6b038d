// PLISimulation through VTK: closed-form intensities of a uniform slab (docs/pli-simulation.md
// §4.2, S-6), extents and field data, sub-extent = crop, thread and seed reproducibility, bad
// input.
#include "ErrorCatcher.h"
#include "FiberPolyData.h"
#include "FiberTestData.h"
#include "PLI/TissueExport.h"
#include "vtkFiberCubeSource.h"
#include "vtkPLISimulation.h"

#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkPointData.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace
{
constexpr double kDeg = M_PI / 180.0;
constexpr double kI0 = 26000.0;

/// One straight fiber of radius 1000 µm through the origin at direction phi and inclination alpha
/// (degrees): every voxel of a small section is inside it (S-6).
vtkSmartPointer<vtkPolyData> Slab(double phiDeg, double alphaDeg)
{
  const double u[3] = { std::cos(alphaDeg * kDeg) * std::cos(phiDeg * kDeg),
    std::cos(alphaDeg * kDeg) * std::sin(phiDeg * kDeg), std::sin(alphaDeg * kDeg) };
  return MakeFibers({ { { -2000 * u[0], -2000 * u[1], -2000 * u[2], 1000 },
    { 2000 * u[0], 2000 * u[1], 2000 * u[2], 1000 } } });
}

/// S-6 set-up: VOI x,y in [-10,10], z in [-30,30], voxel 1, pixel 2, blur 0.71 px, no noise.
void SetUpS6(vtkPLISimulation* sim)
{
  sim->SetVolumeOfInterest(-10, 10, -10, 10, -30, 30);
  sim->SetVoxelSize(1.0);
  sim->SetPixelSize(2.0);
  sim->SetOpticalSigma(0.71);
  sim->SetNoiseGain(0.0);
  sim->SetNumberOfRotations(18);
  sim->SetLayers("1 -0.001 0 p");
  sim->SetNumberOfThreads(2);
}

/// Direction (deg, [0,180)) and retardation of I(ρ) = a0·(1 + r·sin 2(ρ − φ)) from the first
/// Fourier coefficients over equidistant angles (independent of the Core's analysis code).
void Epa(const double* I, int n, double& mean, double& dirDeg, double& ret)
{
  double a0 = 0, a1 = 0, b1 = 0;
  for (int k = 0; k < n; ++k)
  {
    const double rho = k * M_PI / n;
    a0 += I[k] / n;
    a1 += 2.0 * I[k] * std::cos(2 * rho) / n;
    b1 += 2.0 * I[k] * std::sin(2 * rho) / n;
  }
  mean = a0;
  ret = std::hypot(a1, b1) / a0;
  dirDeg = std::fmod(0.5 * std::atan2(-a1, b1) / kDeg + 180.0, 180.0);
}

double CircularDiff180(double a, double b)
{
  const double d = std::fmod(std::fabs(a - b), 180.0);
  return std::min(d, 180.0 - d);
}

double Field(vtkImageData* img, const char* name, int i = 0)
{
  vtkDataArray* a = img->GetFieldData()->GetArray(name);
  EXPECT_NE(a, nullptr) << name;
  return a ? a->GetComponent(i, 0) : NAN;
}

void ExpectSameArrays(vtkImageData* a, vtkImageData* b, const char* name)
{
  vtkDataArray* x = a->GetPointData()->GetArray(name);
  vtkDataArray* y = b->GetPointData()->GetArray(name);
  ASSERT_NE(x, nullptr);
  ASSERT_NE(y, nullptr);
  ASSERT_EQ(x->GetNumberOfTuples(), y->GetNumberOfTuples());
  ASSERT_EQ(x->GetNumberOfComponents(), y->GetNumberOfComponents());
  std::size_t differ = 0;
  for (vtkIdType t = 0; t < x->GetNumberOfTuples(); ++t)
    for (int c = 0; c < x->GetNumberOfComponents(); ++c)
      differ += x->GetComponent(t, c) != y->GetComponent(t, c);
  EXPECT_EQ(differ, 0u) << name;
}

/// A few crossing fibers, not uniform, so crops, threads and seeds are really tested.
vtkSmartPointer<vtkPolyData> SmallModel()
{
  return MakeFibers({ { { -12, -3, -2, 2.0 }, { 0, -2, 1, 2.0 }, { 12, -1, 0, 2.0 } },
    { { -2, -12, 3, 1.5 }, { 1, 0, -2, 1.5 }, { 3, 12, 1, 1.5 } },
    { { -12, 7, -4, 2.5 }, { 12, 4, 5, 2.5 } } });
}

/// The section of SmallModel's tests: a 20 × 16 × 10 µm box, 0.5 µm voxels, 1 µm pixels, 6 angles.
void SetUpSmallSection(vtkPLISimulation* s, vtkPolyData* fibers)
{
  s->SetInputData(fibers);
  s->SetVolumeOfInterest(-10, 10, -8, 8, -5, 5);
  s->SetVoxelSize(0.5);
  s->SetPixelSize(1.0);
  s->SetNumberOfRotations(6);
}
} // namespace

TEST(PLISimulation, UniformSlabGivesTheClosedForm)
{
  const double phi = 30.0, alpha = 20.0;
  vtkNew<vtkPLISimulation> sim;
  sim->SetInputData(Slab(phi, alpha));
  SetUpS6(sim);
  sim->Update();
  vtkImageData* out = sim->GetOutput();
  int ext[6];
  out->GetExtent(ext);
  EXPECT_EQ(ext[0], 0);
  EXPECT_EQ(ext[1], 9);
  EXPECT_EQ(ext[3], 9);
  EXPECT_EQ(ext[4], 0);
  EXPECT_EQ(ext[5], 0);
  double origin[3], spacing[3];
  out->GetOrigin(origin);
  out->GetSpacing(spacing);
  EXPECT_DOUBLE_EQ(origin[0], -9.0);
  EXPECT_DOUBLE_EQ(origin[1], -9.0);
  EXPECT_DOUBLE_EQ(spacing[0], 2.0);
  vtkDataArray* I = out->GetPointData()->GetArray("intensity");
  ASSERT_NE(I, nullptr);
  ASSERT_EQ(I->GetNumberOfComponents(), 18);
  EXPECT_EQ(out->GetPointData()->GetArray("intensity_tilt_0"), nullptr);
  // δ = 2π·Δn·d·cos²α/λ, d = 60 µm; Δn < 0: I(ρ) = I0/4·(1 + |sin δ|·sin 2(ρ − φ)).
  const double delta = 2 * M_PI * 0.001 * 60e-6 * std::pow(std::cos(alpha * kDeg), 2) / 525e-9;
  double worst = 0;
  for (vtkIdType t = 0; t < I->GetNumberOfTuples(); ++t)
    for (int k = 0; k < 18; ++k)
    {
      const double rho = k * 10.0 * kDeg;
      const double expected = kI0 / 4 * (1 + std::sin(delta) * std::sin(2 * (rho - phi * kDeg)));
      worst = std::max(worst, std::fabs(I->GetComponent(t, k) - expected));
    }
  EXPECT_LE(worst, 1e-6 * kI0);
  EXPECT_NEAR(std::sin(delta), 0.592436, 1e-6); // S-6 table, untilted retardation
  vtkDataArray* angles = out->GetFieldData()->GetArray("polarizer_angles");
  ASSERT_NE(angles, nullptr);
  ASSERT_EQ(angles->GetNumberOfTuples(), 18);
  EXPECT_NEAR(angles->GetComponent(17, 0), 170.0, 1e-12);
  EXPECT_DOUBLE_EQ(Field(out, "section_thickness"), 60.0);
  EXPECT_DOUBLE_EQ(Field(out, "wavelength"), 525.0);
  EXPECT_DOUBLE_EQ(Field(out, "tilt_angle"), 0.0);
  EXPECT_DOUBLE_EQ(Field(out, "noise_gain"), 0.0);
  EXPECT_EQ(Field(out, "tilt_convention"), 0.0);
  EXPECT_EQ(Field(out, "empty_section"), 0.0);
  // Untilted only: no tilted view, so the per-view lists are empty.
  ASSERT_NE(out->GetFieldData()->GetArray("tilt_directions"), nullptr);
  EXPECT_EQ(out->GetFieldData()->GetArray("tilt_directions")->GetNumberOfTuples(), 0);
  EXPECT_EQ(out->GetFieldData()->GetArray("tilt_angles")->GetNumberOfTuples(), 0);
}

TEST(PLISimulation, TiltedSlabMatchesS6TableAndAbsorption)
{
  vtkNew<vtkPLISimulation> sim;
  sim->SetInputData(Slab(30.0, 20.0));
  SetUpS6(sim);
  sim->SetTiltAngle(5.5);
  sim->Update();
  vtkImageData* out = sim->GetOutput();
  // S-6 table, Physical convention: direction (deg) / retardation per view.
  const double table[5][2] = { { 30.0, 0.592436 }, { 31.1522, 0.560579 }, { 28.1205, 0.576308 },
    { 29.1380, 0.622326 }, { 31.5904, 0.611887 } };
  const char* names[5] = { "intensity", "intensity_tilt_0", "intensity_tilt_1", "intensity_tilt_2",
    "intensity_tilt_3" };
  for (int v = 0; v < 5; ++v)
  {
    vtkDataArray* I = out->GetPointData()->GetArray(names[v]);
    ASSERT_NE(I, nullptr) << names[v];
    for (vtkIdType t = 0; t < I->GetNumberOfTuples(); t += 7)
    {
      double buf[18], mean, dir, ret;
      for (int k = 0; k < 18; ++k)
        buf[k] = I->GetComponent(t, k);
      Epa(buf, 18, mean, dir, ret);
      EXPECT_NEAR(2 * mean, 13000.0, 13000.0 * 1e-6) << names[v];
      EXPECT_LE(CircularDiff180(dir, table[v][0]), 1e-4) << names[v] << " dir " << dir;
      EXPECT_NEAR(ret, table[v][1], 1e-6) << names[v];
    }
  }
  EXPECT_NEAR(Field(out, "tilt_angle"), 5.5, 1e-12);
  for (int v = 0; v < 4; ++v)
  {
    EXPECT_NEAR(Field(out, "tilt_angles", v), 5.5, 1e-12);
    EXPECT_EQ(Field(out, "tilt_directions", v), 90.0 * v);
  }

  // μ = 5/mm: transmittance 2·mean = I0/2·exp(−μ·path), path 60 µm (untilted) or 60/cos 5.5°.
  sim->SetLayers("1 -0.001 5 p");
  sim->Update();
  for (int v = 0; v < 5; ++v)
  {
    vtkDataArray* I = sim->GetOutput()->GetPointData()->GetArray(names[v]);
    double buf[18], mean, dir, ret;
    for (int k = 0; k < 18; ++k)
      buf[k] = I->GetComponent(12, k);
    Epa(buf, 18, mean, dir, ret);
    const double path = v == 0 ? 0.060 : 0.060 / std::cos(5.5 * kDeg);
    EXPECT_NEAR(2 * mean, 13000.0 * std::exp(-5.0 * path), 13000.0 * 1e-6) << names[v];
  }
}

TEST(PLISimulation, SubExtentEqualsCropOfTheWholeImage)
{
  auto fibers = SmallModel();
  auto configure = [&](vtkPLISimulation* s)
  {
    SetUpSmallSection(s, fibers);
    s->SetTiltAngle(5.5);
    s->SetNoiseGain(3.0);
    s->SetSeed(7);
    s->SetNumberOfThreads(2);
  };
  vtkNew<vtkPLISimulation> whole;
  configure(whole);
  whole->Update();
  vtkImageData* all = whole->GetOutput();
  int wext[6];
  all->GetExtent(wext);
  ASSERT_EQ(wext[1], 19);
  ASSERT_EQ(wext[3], 15);

  vtkNew<vtkPLISimulation> part;
  configure(part);
  const int sub[6] = { 3, 11, 9, 15, 0, 0 };
  part->UpdateExtent(sub);
  vtkImageData* piece = part->GetOutput();
  int pext[6];
  piece->GetExtent(pext);
  for (int a = 0; a < 6; ++a)
    EXPECT_EQ(pext[a], sub[a]);
  for (const char* name : { "intensity", "intensity_tilt_2" })
  {
    vtkDataArray* p = piece->GetPointData()->GetArray(name);
    vtkDataArray* w = all->GetPointData()->GetArray(name);
    ASSERT_NE(p, nullptr);
    std::size_t differ = 0;
    for (int j = sub[2]; j <= sub[3]; ++j)
      for (int i = sub[0]; i <= sub[1]; ++i)
      {
        int ijk[3] = { i, j, 0 };
        const vtkIdType pi = piece->ComputePointId(ijk), wi = all->ComputePointId(ijk);
        for (int k = 0; k < 6; ++k)
          differ += p->GetComponent(pi, k) != w->GetComponent(wi, k);
      }
    EXPECT_EQ(differ, 0u) << name;
  }
  double po[3], wo[3];
  piece->GetOrigin(po);
  all->GetOrigin(wo);
  EXPECT_EQ(po[0], wo[0]);
  EXPECT_EQ(po[1], wo[1]);
}

TEST(PLISimulation, ThreadCountAndSeed)
{
  auto fibers = SmallModel();
  auto run = [&](int threads, int seed)
  {
    vtkNew<vtkPLISimulation> s;
    s->SetInputData(fibers);
    s->SetVolumeOfInterest(-10, 10, -10, 10, -5, 5);
    s->SetVoxelSize(0.5);
    s->SetPixelSize(1.0);
    s->SetNumberOfRotations(9);
    s->SetTiltAngle(5.5);
    s->SetNoiseGain(3.0);
    s->SetSeed(seed);
    s->SetNumberOfThreads(threads);
    s->Update();
    vtkSmartPointer<vtkImageData> out = s->GetOutput();
    return out;
  };
  auto a = run(1, 5), b = run(2, 5), c = run(4, 5), d = run(2, 6);
  for (const char* name : { "intensity", "intensity_tilt_1" })
  {
    ExpectSameArrays(a, b, name);
    ExpectSameArrays(a, c, name);
  }
  vtkDataArray* x = a->GetPointData()->GetArray("intensity");
  vtkDataArray* y = d->GetPointData()->GetArray("intensity");
  std::size_t differ = 0;
  for (vtkIdType t = 0; t < x->GetNumberOfTuples(); ++t)
    differ += x->GetComponent(t, 0) != y->GetComponent(t, 0);
  EXPECT_GT(differ, static_cast<std::size_t>(x->GetNumberOfTuples() / 2))
    << "another Seed must change the noise";
}

TEST(PLISimulation, NoiseHasTheCameraStatistics)
{
  // Uniform slab, no blur: noiseless I(ρ) is known, noisy counts have mean I and variance g·I.
  auto run = [](double gain)
  {
    vtkNew<vtkPLISimulation> s;
    s->SetInputData(Slab(30.0, 20.0));
    SetUpS6(s);
    s->SetPixelSize(1.0);
    s->SetOpticalSigma(0.0);
    s->SetNoiseGain(gain);
    s->SetSeed(11);
    s->Update();
    vtkSmartPointer<vtkImageData> out = s->GetOutput();
    return out;
  };
  auto clean = run(0.0), noisy = run(3.0);
  vtkDataArray* c = clean->GetPointData()->GetArray("intensity");
  vtkDataArray* n = noisy->GetPointData()->GetArray("intensity");
  double sumDiff = 0, sumSq = 0, sumI = 0;
  const vtkIdType count = c->GetNumberOfTuples() * 18;
  for (vtkIdType t = 0; t < c->GetNumberOfTuples(); ++t)
    for (int k = 0; k < 18; ++k)
    {
      const double d = n->GetComponent(t, k) - c->GetComponent(t, k);
      sumDiff += d;
      sumSq += d * d;
      sumI += c->GetComponent(t, k);
    }
  ASSERT_EQ(count, 400 * 18);
  const double meanI = sumI / count;
  // sd of the mean difference = sqrt(3·I/count) ≈ 1.6: allow 5 sd.
  EXPECT_LT(std::fabs(sumDiff / count), 5 * std::sqrt(3 * meanI / count));
  EXPECT_NEAR(sumSq / count / meanI, 3.0, 0.25);
  EXPECT_EQ(Field(noisy, "noise_gain"), 3.0);
}

TEST(PLISimulation, BadInputIsReportedAndRecovers)
{
  vtkNew<vtkPLISimulation> sim;
  vtkNew<ErrorCatcher> catcher;
  catcher->Watch(sim);
  sim->SetInputData(Slab(30.0, 20.0));
  SetUpS6(sim);
  auto expectError = [&](const char* what) { ExpectUpdateError(sim, catcher, what); };
  auto expectGood = [&]()
  {
    catcher->Clear();
    sim->Update();
    EXPECT_TRUE(catcher->Errors.empty()) << catcher->Errors;
    EXPECT_EQ(sim->GetOutput()->GetNumberOfPoints(), 100);
    EXPECT_NE(sim->GetOutput()->GetPointData()->GetArray("intensity"), nullptr);
  };
  expectGood();

  sim->SetVoxelSize(0.0);
  expectError("VoxelSize");
  sim->SetVoxelSize(-1.0);
  expectError("VoxelSize");
  sim->SetVoxelSize(1.0);
  expectGood();

  sim->SetVolumeOfInterest(-10, 10, 10, -10, -30, 30); // y only reversed
  expectError("VolumeOfInterest y");
  sim->SetVolumeOfInterest(-10, 10, -10, 10, -30, 30);
  expectGood();

  sim->SetVolumeOfInterest(-1e6, 1e6, -1e6, 1e6, -30, 30); // 2e6² columns: far beyond 16 GiB
  expectError("GiB");
  sim->SetVolumeOfInterest(-10, 10, -10, 10, -30, 30);
  expectGood();

  sim->SetPixelSize(0.5);
  expectError("PixelSize");
  sim->SetPixelSize(2.0);
  sim->SetLayers("1 -0.001 0 q");
  expectError("Layers");
  sim->SetLayers("1 -0.001 0 p");
  expectGood();

  // A list count far beyond the Core maximum: an error at once (no 16 GB resize) and at run time.
  catcher->Clear();
  sim->SetNumberOfRotationAngles(2147483647);
  EXPECT_NE(
    catcher->Errors.find("RotationAngles has 2147483647 values, at most 3600"), std::string::npos)
    << catcher->Errors;
  EXPECT_EQ(sim->GetNumberOfRotationAngles(), 3601);
  expectError("RotationAngles");
  sim->SetNumberOfTiltAzimuths(-1);
  EXPECT_NE(catcher->Errors.find("TiltAzimuths has -1 values"), std::string::npos)
    << catcher->Errors;
  sim->SetNumberOfTiltAzimuths(0);
  sim->SetNumberOfRotationAngles(0);
  expectGood();

  auto noRadius = MakeFibers({ { { -20, 0, 0, 1 }, { 20, 0, 0, 1 } } }, false);
  sim->SetInputData(noRadius);
  expectError("radius");
  sim->SetInputData(Slab(30.0, 20.0));
  expectGood();

  // Bounds sentinel with a missing radius: found in RequestInformation, reported once.
  sim->SetVolumeOfInterest(1, -1, 1, -1, 1, -1);
  sim->SetInputData(noRadius);
  expectError("radius");
  sim->SetInputData(MakeFibers({ { { -3, -2, -1, 1 }, { 3, 2, 1, 1 } } }));
  catcher->Clear();
  sim->Update();
  EXPECT_TRUE(catcher->Errors.empty()) << catcher->Errors;
  int ext[6];
  sim->GetOutput()->GetExtent(ext);
  // Bounds with radii: x [-4, 4] → 8 voxels → 4 pixels of 2 µm; y [-3, 3] → 3 pixels.
  EXPECT_EQ(ext[1], 3);
  EXPECT_EQ(ext[3], 2);
  EXPECT_DOUBLE_EQ(Field(sim->GetOutput(), "section_thickness"), 4.0);
}

TEST(PLISimulation, EmptySectionAndEmptyInput)
{
  vtkNew<vtkPLISimulation> sim;
  vtkNew<ErrorCatcher> catcher;
  catcher->Watch(sim);
  // A fiber far outside the section: background only, one warning.
  sim->SetInputData(MakeFibers({ { { 500, 500, 0, 1 }, { 600, 500, 0, 1 } } }));
  SetUpS6(sim);
  sim->SetTiltAngle(5.5);
  sim->Update();
  EXPECT_TRUE(catcher->Errors.empty()) << catcher->Errors;
  EXPECT_NE(catcher->Warnings.find("no fiber in the section"), std::string::npos)
    << catcher->Warnings;
  vtkImageData* out = sim->GetOutput();
  EXPECT_EQ(Field(out, "empty_section"), 1.0);
  // No tissue: every intensity is I0/4 (polarizer, λ/4 plate, crossed analyser; §4.2).
  for (const char* name : { "intensity", "intensity_tilt_3" })
  {
    vtkDataArray* I = out->GetPointData()->GetArray(name);
    ASSERT_NE(I, nullptr);
    double worst = 0;
    for (vtkIdType t = 0; t < I->GetNumberOfTuples(); ++t)
      for (int k = 0; k < 18; ++k)
        worst = std::max(worst, std::fabs(I->GetComponent(t, k) - kI0 / 4));
    EXPECT_LE(worst, 1e-9 * kI0) << name;
  }

  // Empty input: empty output, no error, no warning.
  catcher->Clear();
  sim->SetInputData(vtkSmartPointer<vtkPolyData>::New());
  sim->Update();
  EXPECT_TRUE(catcher->Errors.empty()) << catcher->Errors;
  EXPECT_EQ(sim->GetOutput()->GetNumberOfPoints(), 0);
  sim->SetVolumeOfInterest(1, -1, 1, -1, 1, -1);
  sim->Update();
  EXPECT_TRUE(catcher->Errors.empty()) << catcher->Errors;
  EXPECT_EQ(sim->GetOutput()->GetNumberOfPoints(), 0);
}

// Overlapping fibers warn only when the input says it is collision-free (FiberCollisionSolver's
// field data collisions = 0): a model straight from a source is simulated as it is, silently.
TEST(PLISimulation, OverlapWarnsOnlyForAModelThatClaimsToBeSolved)
{
  vtkNew<vtkPLISimulation> sim;
  vtkNew<ErrorCatcher> catcher;
  catcher->Watch(sim);
  // Two fibers of radius 2 crossing at the origin: they share the voxels around it.
  vtkSmartPointer<vtkPolyData> crossing =
    MakeFibers({ { { -8, 0, 0, 2 }, { 8, 0, 0, 2 } }, { { 0, -8, 0, 2 }, { 0, 8, 0, 2 } } });
  sim->SetInputData(crossing);
  sim->SetVolumeOfInterest(-6, 6, -6, 6, -3, 3);
  sim->SetVoxelSize(0.5);
  sim->SetNoiseGain(0.0);
  sim->Update();
  EXPECT_TRUE(catcher->Errors.empty()) << catcher->Errors;
  EXPECT_TRUE(catcher->Warnings.empty()) << catcher->Warnings;
  // The same fibers marked as solved: now the overlap is a surprise worth a warning.
  vtkNew<vtkIntArray> collisions;
  collisions->SetName("collisions");
  collisions->InsertNextValue(0);
  crossing->GetFieldData()->AddArray(collisions);
  crossing->Modified();
  sim->Update();
  EXPECT_TRUE(catcher->Errors.empty()) << catcher->Errors;
  EXPECT_NE(catcher->Warnings.find("fibers overlap although the input is collision-free"),
    std::string::npos)
    << catcher->Warnings;
  // A solver's record of collisions left (it warned itself) does not repeat the warning.
  catcher->Clear();
  collisions->SetValue(0, 3);
  crossing->Modified();
  sim->Update();
  EXPECT_TRUE(catcher->Warnings.empty()) << catcher->Warnings;
}

// Output port 1: the tissue of TissueVolume is the Core's export of the same box (the Core test
// compares that with a brute-force voxelisation), a sub-extent is its crop, and updating one
// port leaves the other port's data alone (no re-run of the simulation).
TEST(PLISimulation, TissuePortIsTheCoreVoxelisationAndLeavesTheImageAlone)
{
  auto fibers = SmallModel();
  auto configure = [&](vtkPLISimulation* s)
  {
    SetUpSmallSection(s, fibers);
    s->SetLayers("0.6 -0.004 5 p; 1 0.004 1 r");
    s->SetExportTissue(1);
    s->SetTissueVolume(-4, 6, -8, 0, -2, 2);
    s->SetNumberOfThreads(1);
  };
  vtkNew<vtkPLISimulation> sim;
  configure(sim);
  sim->Update(0);
  vtkImageData* image = sim->GetOutput(0);
  vtkImageData* tissue = sim->GetOutput(1);
  ASSERT_NE(image->GetPointData()->GetArray("intensity"), nullptr);
  EXPECT_EQ(tissue->GetNumberOfPoints(), 0); // not asked for yet
  const vtkMTimeType imageTime = image->GetMTime();

  sim->Update(1);
  EXPECT_EQ(image->GetMTime(), imageTime);
  EXPECT_NE(image->GetPointData()->GetArray("intensity"), nullptr);
  int ext[6];
  tissue->GetExtent(ext);
  // Voxel centres −9.75 + 0.5·i in [−4, 6]: i = 12 … 31; y: −7.75 + 0.5·j in [−8, 0]: 0 … 15;
  // z: −4.75 + 0.5·k in [−2, 2]: 6 … 13.
  const int expected[6] = { 12, 31, 0, 15, 6, 13 };
  for (int a = 0; a < 6; ++a)
    EXPECT_EQ(ext[a], expected[a]);
  EXPECT_DOUBLE_EQ(tissue->GetOrigin()[0], -9.75);
  EXPECT_DOUBLE_EQ(tissue->GetSpacing()[2], 0.5);
  vtkDataArray* label = tissue->GetPointData()->GetArray("label");
  vtkDataArray* axis = tissue->GetPointData()->GetArray("optic_axis");
  ASSERT_NE(label, nullptr);
  ASSERT_NE(axis, nullptr);
  EXPECT_EQ(axis->GetNumberOfComponents(), 3);
  EXPECT_EQ(Field(tissue, "layers_per_bundle"), 2.0);

  // The same box through the Core.
  fiberpli::FiberConversion in = fiberpli::FiberPolyData::ToModel(fibers, "test");
  ASSERT_TRUE(in.ok());
  fiberpli::pli::PLIOptions o;
  const double voi[6] = { -10, 10, -8, 8, -5, 5 };
  std::copy(voi, voi + 6, o.volumeOfInterest);
  o.voxelSize = 0.5;
  o.pixelSize = 1.0;
  o.layers = "0.6 -0.004 5 p; 1 0.004 1 r";
  fiberpli::pli::PLIPlan plan;
  ASSERT_TRUE(fiberpli::pli::planPLI(in.model, o, plan).ok());
  const double box[6] = { -4, 6, -8, 0, -2, 2 };
  fiberpli::pli::VoxelBox vb;
  ASSERT_TRUE(fiberpli::pli::tissueBox(plan, box, vb).ok());
  fiberpli::pli::TissueVolume tv;
  ASSERT_TRUE(fiberpli::pli::exportTissue(in.model, plan, o, vb, tv).ok());
  ASSERT_EQ(label->GetNumberOfTuples(), static_cast<vtkIdType>(tv.label.size()));
  std::size_t differ = 0, labelled = 0;
  for (vtkIdType p = 0; p < label->GetNumberOfTuples(); ++p)
  {
    differ += label->GetComponent(p, 0) != tv.label[static_cast<std::size_t>(p)];
    labelled += tv.label[static_cast<std::size_t>(p)] > 0;
    for (int c = 0; c < 3; ++c)
      differ += axis->GetComponent(p, c) != tv.axis[3 * static_cast<std::size_t>(p) + c];
  }
  EXPECT_EQ(differ, 0u);
  EXPECT_GT(labelled, 100u);

  sim->Update(0); // nothing changed: no re-run
  EXPECT_EQ(image->GetMTime(), imageTime);

  // A sub-extent of the tissue port is the crop of the whole box.
  vtkNew<vtkPLISimulation> part;
  configure(part);
  int sub[6] = { 15, 20, 3, 9, 7, 12 };
  vtkNew<vtkInformationVector> requests; // one information object per output port
  vtkNew<vtkInformation> none, request;
  request->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), sub, 6);
  requests->SetInformationObject(0, none);
  requests->SetInformationObject(1, request);
  part->Update(1, requests);
  vtkImageData* piece = part->GetOutput(1);
  int pext[6];
  piece->GetExtent(pext);
  for (int a = 0; a < 6; ++a)
    EXPECT_EQ(pext[a], sub[a]);
  std::size_t cropDiffer = 0;
  for (int k = sub[4]; k <= sub[5]; ++k)
    for (int j = sub[2]; j <= sub[3]; ++j)
      for (int i = sub[0]; i <= sub[1]; ++i)
      {
        int ijk[3] = { i, j, k };
        cropDiffer +=
          piece->GetPointData()->GetArray("label")->GetComponent(piece->ComputePointId(ijk), 0) !=
          label->GetComponent(tissue->ComputePointId(ijk), 0);
      }
  EXPECT_EQ(cropDiffer, 0u);

  // Without ExportTissue the port stays empty.
  sim->SetExportTissue(0);
  sim->Update(1);
  EXPECT_EQ(sim->GetOutput(1)->GetNumberOfPoints(), 0);
}

TEST(PLISimulation, PeriodicCellTilesAVolumeOfInterestLargerThanTheCell)
{
  vtkNew<vtkFiberCubeSource> cube;
  cube->SetPopulations(2);
  cube->SetEdgeLength(12.0);
  cube->SetPeriodic(true);
  cube->SetVolumeFraction(0.3);
  cube->SetSeed(3);
  cube->Update();
  auto run = [&](vtkPolyData* fibers)
  {
    vtkNew<vtkPLISimulation> s;
    s->SetInputData(fibers);
    s->SetVolumeOfInterest(-6, 18, -6, 6, -6, 6); // two cells along x
    s->SetVoxelSize(0.5);
    s->SetPixelSize(1.0);
    s->SetOpticalSigma(0.0);
    s->SetNoiseGain(0.0);
    s->SetNumberOfRotations(4);
    s->SetNumberOfThreads(2);
    s->Update();
    vtkSmartPointer<vtkImageData> out = s->GetOutput();
    return out;
  };
  // With the cell, column i and column i + 12 (one period to the right) see the same tissue.
  vtkSmartPointer<vtkImageData> tiled = run(cube->GetOutput());
  int dims[3];
  tiled->GetDimensions(dims);
  ASSERT_EQ(dims[0], 24);
  vtkDataArray* I = tiled->GetPointData()->GetArray("intensity");
  ASSERT_NE(I, nullptr);
  auto differing = [&](vtkDataArray* a)
  {
    int n = 0;
    for (int j = 0; j < dims[1]; ++j)
      for (int i = 0; i < 12; ++i)
        for (int c = 0; c < a->GetNumberOfComponents(); ++c)
          n += std::fabs(a->GetComponent(j * dims[0] + i, c) -
                 a->GetComponent(j * dims[0] + i + 12, c)) > 1e-6 * kI0;
    return n;
  };
  EXPECT_EQ(differing(I), 0);
  // Without it the right half holds only what sticks out of the cell: the test can tell.
  vtkNew<vtkPolyData> open;
  open->DeepCopy(cube->GetOutput());
  open->GetFieldData()->RemoveArray("periodic_cell");
  vtkSmartPointer<vtkImageData> plain = run(open);
  EXPECT_GT(differing(plain->GetPointData()->GetArray("intensity")), 100);
}

TEST(PLISimulation, EnumerationsSwitchesAndSeedOutOfRangeAreNamedNotClamped)
{
  // The setters used to clamp silently (Interpolation 7 → Slerp, TiltConvention 5 → FastPLI,
  // Seed -1 → 0); the Core's enum conversion refuses every other code, never casting it (256
  // would have wrapped to nearest in the 8-bit enum).
  vtkNew<vtkPLISimulation> sim;
  vtkNew<ErrorCatcher> catcher;
  catcher->Watch(sim);
  sim->SetInputData(Slab(30.0, 20.0));
  SetUpS6(sim);
  sim->SetVoxelSize(1.0);
  sim->SetVolumeOfInterest(-10, 10, -10, 10, -30, 30);
  auto expectError = [&](const std::string& text) { ExpectUpdateError(sim, catcher, text); };
  auto expectGood = [&]()
  {
    catcher->Clear();
    sim->Update();
    EXPECT_TRUE(catcher->Errors.empty()) << catcher->Errors;
    EXPECT_EQ(sim->GetOutput()->GetNumberOfPoints(), 100);
  };
  expectGood();
  sim->SetInterpolation(3);
  expectError("Interpolation is 3");
  sim->SetInterpolation(256);
  expectError("Interpolation is 256");
  sim->SetInterpolation(-1);
  expectError("Interpolation is -1");
  sim->SetInterpolation(1);
  expectGood();
  sim->SetTiltConvention(2);
  expectError("TiltConvention is 2");
  sim->SetTiltConvention(-1);
  expectError("TiltConvention is -1");
  sim->SetTiltConvention(vtkPLISimulation::FASTPLI);
  expectGood();
  sim->SetTiltedSensor(2);
  expectError("TiltedSensor is 2, must be 0 or 1");
  sim->SetTiltedSensor(0);
  expectGood();
  sim->SetExportTissue(-1);
  expectError("ExportTissue is -1, must be 0 or 1");
  sim->SetExportTissue(0);
  expectGood();
  sim->SetSeed(-1);
  expectError("Seed is -1, must be >= 0");
  sim->SetSeed(7);
  expectGood();
}

// A solved periodic cell (collisions 0): PLISimulation tiles its volume of interest with the
// translates of the closed fibers, whose copies meet end to start at the faces. They are one
// endless fiber each, so the tiled cell does not overlap; a fiber crossing them still does.
TEST(PLISimulation, SolvedPeriodicCellWithClosedFibersDoesNotWarnOverlap)
{
  // Two closed fibers along x (last = first + (12, 0, 0)) and z, 6 µm apart, radius 2.
  vtkSmartPointer<vtkPolyData> cell =
    MakeFibers({ { { 0, 3, 6, 2 }, { 6, 3, 6, 2 }, { 12, 3, 6, 2 } },
      { { 6, 9, 0, 2 }, { 6, 9, 6, 2 }, { 6, 9, 12, 2 } } });
  auto mark = [](vtkPolyData* pd)
  {
    vtkNew<vtkDoubleArray> box;
    box->SetName("periodic_cell");
    for (double v : { 0.0, 12.0, 0.0, 12.0, 0.0, 12.0 })
      box->InsertNextValue(v);
    pd->GetFieldData()->AddArray(box);
    vtkNew<vtkIntArray> collisions;
    collisions->SetName("collisions");
    collisions->InsertNextValue(0);
    pd->GetFieldData()->AddArray(collisions);
  };
  mark(cell);
  vtkNew<vtkPLISimulation> sim;
  vtkNew<ErrorCatcher> catcher;
  catcher->Watch(sim);
  sim->SetInputData(cell);
  sim->SetVolumeOfInterest(0, 12, 0, 12, 0, 12);
  sim->SetVoxelSize(0.5);
  sim->SetNoiseGain(0.0);
  sim->SetNumberOfRotations(4);
  sim->Update();
  EXPECT_TRUE(catcher->Errors.empty()) << catcher->Errors;
  EXPECT_EQ(catcher->Warnings.find("fibers overlap"), std::string::npos) << catcher->Warnings;
  // A third closed fiber along y through the first: a real overlap, warned.
  vtkSmartPointer<vtkPolyData> crossed =
    MakeFibers({ { { 0, 3, 6, 2 }, { 6, 3, 6, 2 }, { 12, 3, 6, 2 } },
      { { 6, 9, 0, 2 }, { 6, 9, 6, 2 }, { 6, 9, 12, 2 } },
      { { 3, 0, 6, 2 }, { 3, 6, 6, 2 }, { 3, 12, 6, 2 } } });
  mark(crossed);
  sim->SetInputData(crossed);
  sim->Update();
  EXPECT_TRUE(catcher->Errors.empty()) << catcher->Errors;
  EXPECT_NE(catcher->Warnings.find("fibers overlap although the input is collision-free"),
    std::string::npos)
    << catcher->Warnings;
}
