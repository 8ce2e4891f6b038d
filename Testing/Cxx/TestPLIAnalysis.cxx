// PLIAnalysis, FiberOrientationMap and FiberOrientationGroundTruth against closed forms
// (docs/pli-analysis.md §6): stacks are built here from I(ρ) = I_T·(1 + r·sin 2(ρ − φ)),
// independent of the simulator; tilted views from the rotation of docs/pli-simulation.md §4.3.
#include "ErrorCatcher.h"
#include "FiberTestData.h"
#include "vtkFiberOrientationGroundTruth.h"
#include "vtkFiberOrientationMap.h"
#include "vtkPLIAnalysis.h"
#include "vtkPLISimulation.h"

#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkUnsignedCharArray.h>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <vector>

namespace
{
constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

struct Pixel
{
  double it, dirDeg, r; // I_T, φ, retardation
};

/// One-row image of the given pixels; `angles` in degrees, written to polarizer_angles unless
/// `writeAngles` is false.
vtkSmartPointer<vtkImageData> MakeStack(const std::vector<double>& angles,
  const std::vector<Pixel>& pixels, bool writeAngles = true, const char* name = "intensity")
{
  auto img = vtkSmartPointer<vtkImageData>::New();
  img->SetExtent(0, static_cast<int>(pixels.size()) - 1, 0, 0, 0, 0);
  img->SetSpacing(2, 2, 2);
  vtkNew<vtkDoubleArray> I;
  I->SetName(name);
  I->SetNumberOfComponents(static_cast<int>(angles.size()));
  I->SetNumberOfTuples(static_cast<vtkIdType>(pixels.size()));
  for (std::size_t p = 0; p < pixels.size(); ++p)
  {
    for (std::size_t k = 0; k < angles.size(); ++k)
    {
      const double v =
        pixels[p].it * (1.0 + pixels[p].r * std::sin(2.0 * (angles[k] - pixels[p].dirDeg) * kDeg));
      I->SetComponent(static_cast<vtkIdType>(p), static_cast<int>(k), v);
    }
  }
  img->GetPointData()->AddArray(I);
  if (writeAngles)
  {
    vtkNew<vtkDoubleArray> a;
    a->SetName("polarizer_angles");
    for (double x : angles)
    {
      a->InsertNextValue(x);
    }
    img->GetFieldData()->AddArray(a);
  }
  return img;
}

std::vector<double> Equidistant(int n)
{
  std::vector<double> a;
  for (int k = 0; k < n; ++k)
  {
    a.push_back(k * 180.0 / n);
  }
  return a;
}

double Value(vtkImageData* img, const char* name, vtkIdType p, int c = 0)
{
  vtkDataArray* a = img->GetPointData()->GetArray(name);
  EXPECT_NE(a, nullptr) << name;
  return a ? a->GetComponent(p, c) : NAN;
}

/// Difference of two directions modulo 180°.
double DirDiff(double a, double b)
{
  const double d = std::fmod(std::fabs(a - b), 180.0);
  return std::min(d, 180.0 - d);
}

void SetField(vtkImageData* img, const char* name, double v)
{
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->InsertNextValue(v);
  img->GetFieldData()->AddArray(a);
}
} // namespace

TEST(PLIAnalysis, EquidistantSinusoids)
{
  // A-2 (as closed forms): T = 2·I_T, direction φ, retardation r; r > 1 is clamped to 1.
  const std::vector<Pixel> px = { { 1000, 26.565051177, 0.5 }, { 1000, 90, 0.3 },
    { 1000, 135, 0.4 }, { 1000, 45, 0.4 }, { 100, 0, 1.5 }, { 500, 0, 0.0 }, { 3250, 179.5, 0.2 } };
  vtkNew<vtkPLIAnalysis> f;
  f->SetInputData(MakeStack(Equidistant(9), px));
  f->SetInclinationMethod(vtkPLIAnalysis::RETARDATION);
  f->SetNumberOfThreads(2);
  f->Update();
  vtkImageData* out = f->GetOutput();
  ASSERT_EQ(out->GetNumberOfPoints(), static_cast<vtkIdType>(px.size()));
  for (std::size_t p = 0; p < px.size(); ++p)
  {
    const vtkIdType i = static_cast<vtkIdType>(p);
    EXPECT_NEAR(Value(out, "transmittance", i), 2 * px[p].it, 1e-9 * px[p].it) << p;
    EXPECT_LT(DirDiff(Value(out, "direction", i), px[p].dirDeg), 1e-6) << p;
    EXPECT_GE(Value(out, "direction", i), 0.0);
    EXPECT_LT(Value(out, "direction", i), 180.0);
    EXPECT_NEAR(Value(out, "retardation", i), std::min(px[p].r, 1.0), 1e-9) << p;
  }
  // Automatic reference = the largest retardation (1.0 here): r = 1 → 0°, r = 0 → 90°.
  EXPECT_NEAR(Value(out, "inclination", 4), 0.0, 1e-9);
  // r = 0 up to rounding (~1e-16): α = 90° − O(√1e-16 rad), hence 1e-5°.
  EXPECT_NEAR(Value(out, "inclination", 5), 90.0, 1e-5);
  EXPECT_EQ(out->GetPointData()->GetArray("inclination_signed"), nullptr);
}

TEST(PLIAnalysis, NonEquidistantAnglesAndMissingAngles)
{
  // Least squares on the actual angles: 2 / 30° / 0.5 to 1e-12, not the misapplied
  // equidistant formula's 2.012922 / 28.931213° / 0.554869.
  vtkNew<vtkPLIAnalysis> f;
  f->SetInputData(MakeStack({ 0, 20, 50, 90, 100, 150 }, { { 1, 30, 0.5 } }));
  f->Update();
  EXPECT_NEAR(Value(f->GetOutput(), "transmittance", 0), 2.0, 1e-12);
  EXPECT_NEAR(Value(f->GetOutput(), "direction", 0), 30.0, 1e-10);
  EXPECT_NEAR(Value(f->GetOutput(), "retardation", 0), 0.5, 1e-12);

  // Without polarizer_angles the angles are k·180°/N.
  vtkNew<vtkPLIAnalysis> g;
  g->SetInputData(MakeStack(Equidistant(6), { { 6500, 0, 0.6579387259 } }, false));
  g->Update();
  EXPECT_NEAR(Value(g->GetOutput(), "transmittance", 0), 13000, 1e-6);
  EXPECT_LT(DirDiff(Value(g->GetOutput(), "direction", 0), 0.0), 1e-6);
  EXPECT_NEAR(Value(g->GetOutput(), "retardation", 0), 0.6579387259, 1e-9);
}

TEST(PLIAnalysis, NoisyStack)
{
  // 200 pixels of (40°, r 0.4) with 0.5 % Gaussian noise: the estimates scatter around the truth.
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, 0.005);
  auto img = MakeStack(Equidistant(18), std::vector<Pixel>(200, { 1000, 40, 0.4 }));
  auto* I = vtkDoubleArray::SafeDownCast(img->GetPointData()->GetArray("intensity"));
  for (vtkIdType k = 0; k < I->GetNumberOfValues(); ++k)
  {
    I->SetValue(k, I->GetValue(k) * (1.0 + noise(rng)));
  }
  vtkNew<vtkPLIAnalysis> f;
  f->SetInputData(img);
  f->Update();
  double meanDir = 0, meanRet = 0, maxDirErr = 0;
  for (vtkIdType p = 0; p < 200; ++p)
  {
    meanDir += Value(f->GetOutput(), "direction", p) / 200;
    meanRet += Value(f->GetOutput(), "retardation", p) / 200;
    maxDirErr = std::max(maxDirErr, DirDiff(Value(f->GetOutput(), "direction", p), 40));
  }
  // σ_φ ≈ σ·√(2/N)/(2r) ≈ 0.2°: the mean is within 0.1°, no pixel beyond 1.5°.
  EXPECT_NEAR(meanDir, 40.0, 0.1);
  EXPECT_NEAR(meanRet, 0.4, 0.005);
  EXPECT_LT(maxDirErr, 1.5);
  EXPECT_GT(maxDirErr, 1e-4); // the noise really is there
}

TEST(PLIAnalysis, InclinationFromRetardation)
{
  // r = |sin(0.7180783208·cos²α)|, r_ref = 0.6579387259.
  const double alphas[] = { 45, 20, 0, 90 };
  std::vector<Pixel> px;
  for (double a : alphas)
  {
    px.push_back({ 1000, 10, std::fabs(std::sin(0.7180783208 * std::pow(std::cos(a * kDeg), 2))) });
  }
  px.push_back({ 1000, 10, 0.7 }); // above r_ref → 0°
  vtkNew<vtkPLIAnalysis> f;
  f->SetInputData(MakeStack(Equidistant(9), px));
  f->SetInclinationMethod(vtkPLIAnalysis::RETARDATION);
  f->SetReferenceRetardation(0.6579387259);
  f->Update();
  for (int p = 0; p < 4; ++p)
  {
    // 90°: the EPA's rounding of r ≈ 0 enters through a square root (1e-5° then).
    EXPECT_NEAR(Value(f->GetOutput(), "inclination", p), alphas[p], alphas[p] == 90 ? 1e-5 : 1e-6)
      << p;
  }
  EXPECT_NEAR(Value(f->GetOutput(), "inclination", 4), 0.0, 1e-6);
  EXPECT_NEAR(f->GetOutput()->GetFieldData()->GetArray("reference_retardation")->GetComponent(0, 0),
    0.6579387259, 1e-12);
}

namespace
{
/// closed-form views of a uniform column (t_rel, axis (dir, incl)) under the Physical
/// convention v_b = Rᵀ(τ, ψ)·v; returns the image with intensity and intensity_tilt_0..3.
vtkSmartPointer<vtkImageData> TiltStack(double dirDeg, double inclDeg, double tRel, double tauDeg,
  int n, std::vector<std::pair<double, double>>* views = nullptr)
{
  const std::vector<double> rho = Equidistant(n);
  const double v[3] = { std::cos(inclDeg * kDeg) * std::cos(dirDeg * kDeg),
    std::cos(inclDeg * kDeg) * std::sin(dirDeg * kDeg), std::sin(inclDeg * kDeg) };
  vtkSmartPointer<vtkImageData> img;
  for (int j = 0; j < 5; ++j)
  {
    double vb[3] = { v[0], v[1], v[2] };
    double t = tRel;
    if (j > 0)
    {
      const double c = std::cos(tauDeg * kDeg), s = std::sin(tauDeg * kDeg);
      const double cp = std::cos((j - 1) * kPi / 2), sp = std::sin((j - 1) * kPi / 2);
      const double R[3][3] = { { c * cp * cp + sp * sp, (c - 1) * sp * cp, s * cp },
        { (c - 1) * sp * cp, c * sp * sp + cp * cp, s * sp }, { -s * cp, -s * sp, c } };
      for (int a = 0; a < 3; ++a)
      {
        vb[a] = R[0][a] * v[0] + R[1][a] * v[1] + R[2][a] * v[2]; // Rᵀ·v
      }
      t = tRel / c;
    }
    const double alpha = std::asin(vb[2]);
    const double phi = std::atan2(vb[1], vb[0]) / kDeg;
    const double r = std::sin(kPi / 2 * t * std::cos(alpha) * std::cos(alpha));
    if (views)
    {
      views->push_back({ std::fmod(phi + 360.0, 180.0), r });
    }
    const std::string name = j == 0 ? "intensity" : "intensity_tilt_" + std::to_string(j - 1);
    auto view = MakeStack(rho, { { 6500, phi, r } }, j == 0, name.c_str());
    if (j == 0)
    {
      img = view;
    }
    else
    {
      img->GetPointData()->AddArray(view->GetPointData()->GetArray(name.c_str()));
    }
  }
  SetField(img, "tilt_angle", tauDeg);
  SetField(img, "noise_gain", 0.0);
  vtkNew<vtkIntArray> conv;
  conv->SetName("tilt_convention");
  conv->InsertNextValue(0);
  img->GetFieldData()->AddArray(conv);
  return img;
}
} // namespace

TEST(PLIAnalysis, TiltFitSignedInclination)
{
  // The closed-form views reproduce the A-4 table (this checks the test's own rotation).
  std::vector<std::pair<double, double>> views;
  TiltStack(30, 20, 0.4571428571, 5.5, 18, &views);
  const double table[5][2] = { { 30.0, 0.592436 }, { 31.1522, 0.560579 }, { 28.1205, 0.576308 },
    { 29.1380, 0.622326 }, { 31.5904, 0.611887 } };
  for (int j = 0; j < 5; ++j)
  {
    EXPECT_NEAR(views[j].first, table[j][0], 1e-4) << j;
    EXPECT_NEAR(views[j].second, table[j][1], 1e-6) << j;
  }

  struct Case
  {
    double dir, incl;
  };
  for (Case c : { Case{ 30, 20 }, Case{ 120, -60 } })
  {
    vtkNew<vtkPLIAnalysis> f;
    f->SetInputData(TiltStack(c.dir, c.incl, 0.4571428571, 5.5, 18));
    f->Update(); // Auto → Tilt
    vtkImageData* out = f->GetOutput();
    EXPECT_EQ(out->GetFieldData()->GetArray("inclination_method")->GetComponent(0, 0), 2);
    EXPECT_LT(DirDiff(Value(out, "direction", 0), c.dir), 1e-4) << c.dir;
    EXPECT_NEAR(Value(out, "inclination_signed", 0), c.incl, 1e-4) << c.dir;
    EXPECT_NEAR(Value(out, "inclination", 0), std::fabs(c.incl), 1e-4) << c.dir;
    EXPECT_NEAR(Value(out, "relative_thickness", 0), 0.4571428571, 1e-6) << c.dir;
    EXPECT_LT(Value(out, "fit_chi2", 0), 1e-12);
  }

  // The convention is read from field data: the wrong one gives the mirrored sign.
  auto wrong = TiltStack(30, 20, 0.4571428571, 5.5, 18);
  vtkIntArray::SafeDownCast(wrong->GetFieldData()->GetArray("tilt_convention"))->SetValue(0, 1);
  vtkNew<vtkPLIAnalysis> g;
  g->SetInputData(wrong);
  g->Update();
  EXPECT_NEAR(Value(g->GetOutput(), "inclination_signed", 0), -20.0, 0.5);

  // Retardation method on the same data ignores the tilts: unsigned, no signed array.
  vtkNew<vtkPLIAnalysis> h;
  h->SetInputData(TiltStack(30, 20, 0.4571428571, 5.5, 18));
  h->SetInclinationMethod(vtkPLIAnalysis::RETARDATION);
  h->SetReferenceRetardation(0.6579387259);
  h->Update();
  EXPECT_NEAR(Value(h->GetOutput(), "inclination", 0), 20.0, 1e-4);
  EXPECT_EQ(h->GetOutput()->GetPointData()->GetArray("inclination_signed"), nullptr);
}

// Tilted views on the tilted sensor's grid (field data tilted_sensor = 1) are not pixel-aligned:
// Tilt is refused with a message naming the cause, Auto falls back to the retardation method.
TEST(PLIAnalysis, TiltFitRefusesTiltedSensorViews)
{
  auto data = TiltStack(30, 20, 0.4571428571, 5.5, 18);
  vtkNew<vtkIntArray> sensor;
  sensor->SetName("tilted_sensor");
  sensor->InsertNextValue(1);
  data->GetFieldData()->AddArray(sensor);
  vtkNew<vtkPLIAnalysis> f;
  vtkNew<ErrorCatcher> catcher;
  catcher->Watch(f);
  f->SetInputData(data);
  f->SetInclinationMethod(vtkPLIAnalysis::TILT);
  f->Update();
  EXPECT_NE(catcher->Errors.find("tilted_sensor = 1"), std::string::npos) << catcher->Errors;
  EXPECT_NE(catcher->Errors.find("TiltedSensor off"), std::string::npos) << catcher->Errors;
  EXPECT_EQ(f->GetOutput()->GetNumberOfPoints(), 0);
  catcher->Clear();
  f->SetInclinationMethod(vtkPLIAnalysis::AUTO);
  f->SetReferenceRetardation(0.6579387259);
  f->Update();
  EXPECT_TRUE(catcher->Errors.empty()) << catcher->Errors;
  vtkImageData* out = f->GetOutput();
  EXPECT_EQ(out->GetFieldData()->GetArray("inclination_method")->GetComponent(0, 0), 1);
  EXPECT_NEAR(Value(out, "inclination", 0), 20.0, 1e-4);
  EXPECT_EQ(out->GetPointData()->GetArray("inclination_signed"), nullptr);
}

// End to end: PLISimulation with TiltedSensor writes tilted_sensor = 1, which PLIAnalysis reads.
TEST(PLIAnalysis, SimulatedTiltedSensorViewsAreRefusedForTheTiltFit)
{
  vtkNew<vtkPLISimulation> sim;
  sim->SetInputData(MakeFibers({ { { -20, -5, -3, 6 }, { 20, 5, 3, 6 } } }));
  sim->SetVolumeOfInterest(-8, 8, -8, 8, -4, 4);
  sim->SetVoxelSize(1.0);
  sim->SetPixelSize(2.0);
  sim->SetNoiseGain(0.0);
  sim->SetTiltAngle(8.0);
  sim->SetNumberOfThreads(1);
  vtkNew<vtkPLIAnalysis> f;
  vtkNew<ErrorCatcher> catcher;
  catcher->Watch(f);
  f->SetInputConnection(sim->GetOutputPort());
  f->SetInclinationMethod(vtkPLIAnalysis::TILT);
  f->Update();
  EXPECT_TRUE(catcher->Errors.empty()) << catcher->Errors; // registered views: the fit runs
  EXPECT_EQ(sim->GetOutput()->GetFieldData()->GetArray("tilted_sensor")->GetComponent(0, 0), 0);
  sim->TiltedSensorOn();
  f->Update();
  EXPECT_EQ(sim->GetOutput()->GetFieldData()->GetArray("tilted_sensor")->GetComponent(0, 0), 1);
  EXPECT_NE(catcher->Errors.find("tilted_sensor = 1"), std::string::npos) << catcher->Errors;
}

TEST(PLIAnalysis, SubExtent)
{
  std::vector<Pixel> px;
  for (int p = 0; p < 10; ++p)
  {
    px.push_back({ 100.0 + p, 15.0 * p, 0.3 });
  }
  vtkNew<vtkPLIAnalysis> f;
  f->SetInputData(MakeStack(Equidistant(6), px));
  f->SetInclinationMethod(vtkPLIAnalysis::RETARDATION);
  f->SetReferenceRetardation(0.5);
  int ext[6] = { 3, 6, 0, 0, 0, 0 };
  f->UpdateExtent(ext);
  vtkImageData* out = f->GetOutput();
  int got[6];
  out->GetExtent(got);
  EXPECT_EQ(got[0], 3);
  EXPECT_EQ(got[1], 6);
  ASSERT_EQ(out->GetNumberOfPoints(), 4);
  for (int p = 0; p < 4; ++p)
  {
    EXPECT_NEAR(Value(out, "transmittance", p), 2 * (103.0 + p), 1e-9);
    EXPECT_LT(DirDiff(Value(out, "direction", p), 15.0 * (3 + p)), 1e-6);
  }
}

TEST(PLIAnalysis, BadInputAndRecovery)
{
  vtkNew<vtkPLIAnalysis> f;
  vtkNew<ErrorCatcher> catcher;
  catcher->Watch(f);

  f->SetInputData(MakeStack(Equidistant(6), { { 1, 0, 0.1 } }, true, "wrong_name"));
  f->Update();
  EXPECT_NE(catcher->Errors.find("'intensity'"), std::string::npos) << catcher->Errors;
  EXPECT_EQ(f->GetOutput()->GetNumberOfPoints(), 0);

  catcher->Clear();
  f->SetInputData(MakeStack({ 0, 90 }, { { 1, 0, 0.1 } }));
  f->Update();
  EXPECT_NE(catcher->Errors.find("at least 3"), std::string::npos) << catcher->Errors;
  EXPECT_EQ(f->GetOutput()->GetNumberOfPoints(), 0);

  catcher->Clear();
  auto mismatch = MakeStack(Equidistant(6), { { 1, 0, 0.1 } });
  mismatch->GetFieldData()->RemoveArray("polarizer_angles");
  SetField(mismatch, "polarizer_angles", 0.0);
  vtkDoubleArray::SafeDownCast(mismatch->GetFieldData()->GetArray("polarizer_angles"))
    ->InsertNextValue(30);
  vtkDoubleArray::SafeDownCast(mismatch->GetFieldData()->GetArray("polarizer_angles"))
    ->InsertNextValue(60);
  f->SetInputData(mismatch);
  f->Update();
  EXPECT_NE(catcher->Errors.find("6 components"), std::string::npos) << catcher->Errors;

  catcher->Clear();
  f->SetInputData(MakeStack(Equidistant(6), { { 1, 0, 0.1 } }));
  f->SetInclinationMethod(vtkPLIAnalysis::TILT); // no tilt stacks
  f->Update();
  EXPECT_FALSE(catcher->Errors.empty());
  EXPECT_EQ(f->GetOutput()->GetNumberOfPoints(), 0);

  // Fixed: a valid output again, and the empty input is no error.
  catcher->Clear();
  f->SetInclinationMethod(vtkPLIAnalysis::AUTO);
  f->Update();
  EXPECT_TRUE(catcher->Errors.empty()) << catcher->Errors;
  EXPECT_NEAR(Value(f->GetOutput(), "transmittance", 0), 2.0, 1e-12);
  vtkNew<vtkImageData> empty;
  f->SetInputData(empty);
  f->Update();
  EXPECT_TRUE(catcher->Errors.empty()) << catcher->Errors;
  EXPECT_EQ(f->GetOutput()->GetNumberOfPoints(), 0);
}

namespace
{
vtkSmartPointer<vtkImageData> AngleImage(const std::vector<std::pair<double, double>>& di)
{
  auto img = vtkSmartPointer<vtkImageData>::New();
  img->SetExtent(0, static_cast<int>(di.size()) - 1, 0, 0, 0, 0);
  vtkNew<vtkDoubleArray> d, i;
  d->SetName("direction");
  i->SetName("inclination");
  for (const auto& p : di)
  {
    d->InsertNextValue(p.first);
    i->InsertNextValue(p.second);
  }
  img->GetPointData()->AddArray(d);
  img->GetPointData()->AddArray(i);
  return img;
}
} // namespace

TEST(FiberOrientationMap, ColoursOfKnownAngles)
{
  //
  const std::vector<std::pair<double, double>> in = { { 0, 0 }, { 15, 0 }, { 30, 0 }, { 45, 0 },
    { 60, 0 }, { 90, 0 }, { 120, 0 }, { 150, 0 }, { 179, 0 }, { 0, 45 }, { 90, 30 }, { 30, 60 },
    { 77, 90 }, { 30, -60 }, { NAN, 0 } };
  const int hsv[][3] = { { 255, 0, 0 }, { 255, 127, 0 }, { 255, 255, 0 }, { 127, 255, 0 },
    { 0, 255, 0 }, { 0, 255, 255 }, { 0, 0, 255 }, { 255, 0, 255 }, { 255, 0, 8 }, { 127, 0, 0 },
    { 0, 170, 170 }, { 85, 85, 0 }, { 0, 0, 0 }, { 85, 85, 0 }, { 0, 0, 0 } };
  const int rgb[][3] = { { 255, 0, 0 }, { 246, 65, 0 }, { 220, 127, 0 }, { 180, 180, 0 },
    { 127, 220, 0 }, { 0, 255, 0 }, { 127, 220, 0 }, { 220, 127, 0 }, { 254, 4, 0 },
    { 180, 0, 180 }, { 0, 220, 127 }, { 110, 63, 220 }, { 0, 0, 255 }, { 110, 63, 220 },
    { 0, 0, 0 } };
  for (int scheme : { vtkFiberOrientationMap::HSV_BLACK, vtkFiberOrientationMap::RGB })
  {
    vtkNew<vtkFiberOrientationMap> f;
    f->SetInputData(AngleImage(in));
    f->SetColorScheme(scheme);
    f->Update();
    auto* fom = vtkUnsignedCharArray::SafeDownCast(f->GetOutput()->GetPointData()->GetScalars());
    ASSERT_NE(fom, nullptr);
    EXPECT_STREQ(fom->GetName(), "fom");
    ASSERT_EQ(fom->GetNumberOfComponents(), 3);
    for (vtkIdType p = 0; p < static_cast<vtkIdType>(in.size()); ++p)
    {
      for (int c = 0; c < 3; ++c)
      {
        EXPECT_EQ(fom->GetComponent(p, c), (scheme == 0 ? hsv : rgb)[p][c])
          << "scheme " << scheme << " pixel " << p;
      }
    }
    EXPECT_NE(f->GetOutput()->GetPointData()->GetArray("direction"), nullptr); // input arrays kept
  }
}

TEST(FiberOrientationMap, LegendPortAndBadInput)
{
  vtkNew<vtkFiberOrientationMap> f;
  vtkNew<ErrorCatcher> catcher;
  catcher->Watch(f);
  f->SetLegendSize(64);
  vtkNew<vtkImageData> noArrays;
  noArrays->SetDimensions(2, 2, 1);
  f->SetInputData(noArrays);
  f->Update(0);
  EXPECT_NE(catcher->Errors.find("'direction'"), std::string::npos) << catcher->Errors;
  EXPECT_EQ(f->GetOutput()->GetNumberOfPoints(), 0);

  catcher->Clear();
  f->SetInputData(AngleImage({ { 30, 0 } }));
  f->Update(1);
  f->Update(0);
  EXPECT_TRUE(catcher->Errors.empty()) << catcher->Errors;
  EXPECT_EQ(f->GetOutput(0)->GetNumberOfPoints(), 1);
  vtkImageData* legend = vtkImageData::SafeDownCast(f->GetOutputDataObject(1));
  int dims[3];
  legend->GetDimensions(dims);
  EXPECT_EQ(dims[0], 64);
  EXPECT_EQ(dims[1], 64);
  auto* c = vtkUnsignedCharArray::SafeDownCast(legend->GetPointData()->GetArray("fom"));
  ASSERT_NE(c, nullptr);
  auto at = [&](int i, int j, int k) { return static_cast<int>(c->GetComponent(i + 64 * j, k)); };
  for (int k = 0; k < 3; ++k)
  {
    EXPECT_EQ(at(0, 0, k), 255); // corner: outside the disc, white
    EXPECT_LE(at(32, 32, k), 8); // centre: steep fiber, black in HSV-black
  }
  // Right rim (x ≈ 1, y ≈ 0): in-plane fiber along x → red; top rim: along y → cyan.
  EXPECT_GT(at(63, 32, 0), 150);
  EXPECT_LT(at(63, 32, 1), 40);
  EXPECT_EQ(at(63, 32, 2), 0);
  EXPECT_LT(at(32, 63, 0), 40);
  EXPECT_GT(at(32, 63, 1), 150);
  EXPECT_GT(at(32, 63, 2), 150);
}

// The input arrays are chosen with SetInputArrayToProcess: other names and other numeric types
// give the same colours as the default direction/inclination doubles.
TEST(FiberOrientationMap, InputArraysAreSelectedByName)
{
  const std::vector<std::pair<double, double>> in = { { 0, 0 }, { 30, 0 }, { 90, 30 }, { 30, 60 },
    { 150, -45 } };
  vtkNew<vtkFiberOrientationMap> reference;
  reference->SetInputData(AngleImage(in));
  reference->Update();
  auto* expected =
    vtkUnsignedCharArray::SafeDownCast(reference->GetOutput()->GetPointData()->GetArray("fom"));
  ASSERT_NE(expected, nullptr);

  auto img = AngleImage({ { 45, 45 } }); // decoy arrays under the default names
  img->SetExtent(0, static_cast<int>(in.size()) - 1, 0, 0, 0, 0);
  vtkNew<vtkFloatArray> d, i;
  d->SetName("my_direction");
  i->SetName("my_inclination");
  vtkNew<vtkDoubleArray> decoyD, decoyI;
  decoyD->SetName("direction");
  decoyI->SetName("inclination");
  for (const auto& p : in)
  {
    d->InsertNextValue(static_cast<float>(p.first));
    i->InsertNextValue(static_cast<float>(p.second));
    decoyD->InsertNextValue(0.0);
    decoyI->InsertNextValue(90.0);
  }
  img->GetPointData()->AddArray(d);
  img->GetPointData()->AddArray(i);
  img->GetPointData()->AddArray(decoyD);
  img->GetPointData()->AddArray(decoyI);
  vtkNew<vtkFiberOrientationMap> f;
  vtkNew<ErrorCatcher> catcher;
  catcher->Watch(f);
  f->SetInputData(img);
  f->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "my_direction");
  f->SetInputArrayToProcess(1, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "my_inclination");
  f->Update();
  EXPECT_TRUE(catcher->Errors.empty()) << catcher->Errors;
  auto* fom = vtkUnsignedCharArray::SafeDownCast(f->GetOutput()->GetPointData()->GetArray("fom"));
  ASSERT_NE(fom, nullptr);
  ASSERT_EQ(fom->GetNumberOfTuples(), expected->GetNumberOfTuples());
  for (vtkIdType k = 0; k < 3 * fom->GetNumberOfTuples(); ++k)
  {
    EXPECT_EQ(fom->GetValue(k), expected->GetValue(k)) << "value " << k;
  }

  // A selected array that is not there is an error naming it.
  catcher->Clear();
  f->SetInputArrayToProcess(1, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "no_such_array");
  f->Update();
  EXPECT_NE(catcher->Errors.find("'no_such_array'"), std::string::npos) << catcher->Errors;
}

TEST(FiberOrientationGroundTruth, StraightFibers)
{
  struct Case
  {
    double dir, incl;
  };
  for (Case c : { Case{ 30, 20 }, Case{ 120, -60 } })
  {
    const double u[3] = { std::cos(c.incl * kDeg) * std::cos(c.dir * kDeg),
      std::cos(c.incl * kDeg) * std::sin(c.dir * kDeg), std::sin(c.incl * kDeg) };
    // One thick straight fiber through the origin covering the whole VOI.
    auto fibers = MakeFibers(
      { { { -40 * u[0], -40 * u[1], -40 * u[2], 10 }, { 40 * u[0], 40 * u[1], 40 * u[2], 10 } } });
    vtkNew<vtkFiberOrientationGroundTruth> f;
    f->SetInputData(fibers);
    f->SetVolumeOfInterest(-3, 3, -3, 3, -1, 1);
    f->SetVoxelSize(0.5);
    f->SetPixelSize(1.0);
    f->SetNumberOfThreads(2);
    f->Update();
    vtkImageData* out = f->GetOutput();
    int ext[6];
    out->GetExtent(ext);
    EXPECT_EQ(ext[1], 5);
    EXPECT_EQ(ext[3], 5);
    EXPECT_EQ(ext[5], 0);
    EXPECT_DOUBLE_EQ(out->GetOrigin()[0], -2.5);
    EXPECT_DOUBLE_EQ(out->GetOrigin()[1], -2.5);
    EXPECT_DOUBLE_EQ(out->GetOrigin()[2], 0.0);
    EXPECT_DOUBLE_EQ(out->GetSpacing()[0], 1.0);
    for (vtkIdType p = 0; p < 36; ++p)
    {
      EXPECT_LT(DirDiff(Value(out, "direction", p), c.dir), 1e-5); // Jacobi eigenvector accuracy
      EXPECT_NEAR(Value(out, "inclination", p), std::fabs(c.incl), 1e-6);
      EXPECT_NEAR(Value(out, "inclination_signed", p), c.incl, 1e-6);
      EXPECT_NEAR(Value(out, "fraction", p), 1.0, 1e-12);
      EXPECT_NEAR(Value(out, "anisotropy", p), 1.0, 1e-9);
    }
    // ...and FiberOrientationMap colours it: (30°, 20°) → H 60°, V 1 − 20/90 → (198, 198, 0).
    if (c.dir == 30)
    {
      vtkNew<vtkFiberOrientationMap> m;
      m->SetInputConnection(f->GetOutputPort());
      m->Update();
      auto* fom = m->GetOutput()->GetPointData()->GetScalars();
      EXPECT_EQ(fom->GetComponent(7, 0), 198);
      EXPECT_EQ(fom->GetComponent(7, 1), 198);
      EXPECT_EQ(fom->GetComponent(7, 2), 0);
    }
  }
}

namespace
{
// The ground-truth tests' input: one fiber along x from 0 to 10 with radius 1, voxels 0.25 µm,
// pixels 1 µm.
void SetUpFiberAlongX(vtkFiberOrientationGroundTruth* f)
{
  f->SetInputData(MakeFibers({ { { 0, 0, 0, 1 }, { 10, 0, 0, 1 } } }));
  f->SetVoxelSize(0.25);
  f->SetPixelSize(1.0);
}
} // namespace

TEST(FiberOrientationGroundTruth, InputBoundsEmptyAndBadInput)
{
  // Sentinel VOI = bounds with radii: fiber along x from 0 to 10, r 1 → [−1, 11] × [−1, 1] × [−1,
  // 1].
  vtkNew<vtkFiberOrientationGroundTruth> f;
  vtkNew<ErrorCatcher> catcher;
  catcher->Watch(f);
  SetUpFiberAlongX(f);
  f->Update();
  int ext[6];
  f->GetOutput()->GetExtent(ext);
  EXPECT_EQ(ext[1], 11);
  EXPECT_EQ(ext[3], 1);
  EXPECT_DOUBLE_EQ(f->GetOutput()->GetOrigin()[0], -0.5);
  EXPECT_DOUBLE_EQ(f->GetOutput()->GetOrigin()[1], -0.5);
  EXPECT_LT(DirDiff(Value(f->GetOutput(), "direction", 5), 0.0), 1e-9);
  // The fiber's disc covers a fraction π/4 of the 2 × 2 cross-section (voxel estimate).
  double sumFraction = 0;
  for (vtkIdType p = 12; p < 24; ++p)
  {
    sumFraction += Value(f->GetOutput(), "fraction", p);
  }
  EXPECT_GT(sumFraction / 12 + 0, 0.3);

  f->SetInputData(MakeFibers({ { { 0, 0, 0, -1 }, { 10, 0, 0, 1 } } }));
  f->Update();
  EXPECT_FALSE(catcher->Errors.empty());
  EXPECT_EQ(f->GetOutput()->GetNumberOfPoints(), 0);
  catcher->Clear();
  f->SetInputData(MakeFibers({ { { 0, 0, 0, 1 }, { 10, 0, 0, 1 } } }));
  f->SetPixelSize(0.1); // < VoxelSize
  f->Update();
  EXPECT_NE(catcher->Errors.find("PixelSize"), std::string::npos) << catcher->Errors;
  catcher->Clear();
  f->SetPixelSize(1.0);
  f->Update();
  EXPECT_TRUE(catcher->Errors.empty()) << catcher->Errors;
  EXPECT_EQ(f->GetOutput()->GetNumberOfPoints(), 24);
  vtkNew<vtkPolyData> empty;
  f->SetInputData(empty);
  f->Update();
  EXPECT_TRUE(catcher->Errors.empty()) << catcher->Errors;
  EXPECT_EQ(f->GetOutput()->GetNumberOfPoints(), 0);
}

TEST(PLIAnalysis, OutOfRangePropertiesAreNamedNotClamped)
{
  // The setters used to clamp silently (InclinationMethod 7 → Tilt, ReferenceRetardation 1.5 → 1,
  // NoiseGain 2e6 → 1e6); the Core's checks now name the property and the value.
  vtkNew<vtkPLIAnalysis> f;
  vtkNew<ErrorCatcher> catcher;
  catcher->Watch(f);
  f->SetInputData(MakeStack(Equidistant(6), { { 1, 0, 0.1 } }));
  const auto expectError = [&](const std::string& text) { ExpectUpdateError(f, catcher, text); };
  const auto expectGood = [&]()
  {
    ExpectUpdateClean(f, catcher);
    ASSERT_EQ(f->GetOutput()->GetNumberOfPoints(), 1);
    EXPECT_NEAR(Value(f->GetOutput(), "transmittance", 0), 2.0, 1e-12);
  };
  expectGood();
  f->SetInclinationMethod(3);
  expectError("InclinationMethod is 3");
  f->SetInclinationMethod(-1);
  expectError("InclinationMethod is -1");
  f->SetInclinationMethod(vtkPLIAnalysis::RETARDATION);
  expectGood();
  f->SetReferenceRetardation(1.5);
  expectError("ReferenceRetardation is 1.5");
  f->SetReferenceRetardation(-0.25);
  expectError("ReferenceRetardation is -0.25");
  f->SetReferenceRetardation(std::nan(""));
  expectError("ReferenceRetardation is nan");
  f->SetReferenceRetardation(0.5);
  expectGood();
  f->SetNoiseGain(-0.5); // neither −1 (from the data) nor a gain
  expectError("NoiseGain is -0.5");
  f->SetNoiseGain(2e6);
  expectError("NoiseGain is 2e+06");
  f->SetNoiseGain(-1.0);
  expectGood();
}

TEST(FiberOrientationGroundTruth, BadSizesAreNamedNotClamped)
{
  // VoxelSize and PixelSize used to be clamped to [1e-3, 1e6] without a word.
  vtkNew<vtkFiberOrientationGroundTruth> f;
  vtkNew<ErrorCatcher> catcher;
  catcher->Watch(f);
  SetUpFiberAlongX(f);
  const auto expectError = [&](const std::string& text) { ExpectUpdateError(f, catcher, text); };
  const auto expectGood = [&]()
  {
    ExpectUpdateClean(f, catcher);
    EXPECT_EQ(f->GetOutput()->GetNumberOfPoints(), 24); // 12 × 2 pixels of [−1, 11] × [−1, 1]
  };
  expectGood();
  f->SetVoxelSize(0.0);
  expectError("VoxelSize is 0");
  f->SetVoxelSize(-0.25);
  expectError("VoxelSize is -0.25");
  f->SetVoxelSize(0.25);
  expectGood();
  f->SetPixelSize(-2.0);
  expectError("PixelSize is -2");
  f->SetPixelSize(1e9); // larger than the section: no pixel
  expectError("PixelSize 1e+09");
  f->SetPixelSize(1.0);
  expectGood();
}
