#include "PLI/PLIPipeline.h"

#include "Model/InnerRadii.h"
#include "PLI/Optics.h"
#include "PLI/OptionLimits.h"
#include "PLI/Simulator.h"
#include "PLI/TissueSpec.h"
#include "Util/EnumCode.h"
#include "Util/MemoryBudget.h"
#include "Util/NumberFormat.h"
#include "Util/ValueCheck.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

namespace fiberpli
{
namespace pli
{

namespace
{
constexpr double kDeg = M_PI / 180.0;

/// "" when every value of the list `name` is finite, inside [lo, hi) (or (lo, hi) when loOpen)
/// and distinct, and the list has at least `minCount` values; else the message naming it.
std::string checkAngleList(const char* name, const std::vector<double>& v, double lo, bool loOpen,
  double hi, std::size_t minCount, std::size_t maxCount)
{
  std::ostringstream m;
  if (v.size() < minCount || v.size() > maxCount)
  {
    m << name << " has " << v.size() << " values, needs " << minCount << " to " << maxCount;
    return m.str();
  }
  for (std::size_t a = 0; a < v.size(); ++a)
  {
    if (!std::isfinite(v[a]) || (loOpen ? !(v[a] > lo) : !(v[a] >= lo)) || !(v[a] < hi))
    {
      m << name << "[" << a << "] is " << v[a] << " deg, must be in " << (loOpen ? "(" : "[") << lo
        << ", " << hi << ")";
      return m.str();
    }
    for (std::size_t b = 0; b < a; ++b)
      if (std::fabs(v[a] - v[b]) < 1e-9)
      {
        m << name << "[" << b << "] and [" << a << "] are both " << v[a]
          << " deg: the values must be distinct";
        return m.str();
      }
  }
  return {};
}

/// The polarimeter set-up of the options: polarizer angles and tilted views (degrees), or an error.
std::string polarimeterSetUp(const PLIOptions& o, std::vector<double>& rotDeg,
  std::vector<double>& tiltDeg, std::vector<double>& azDeg)
{
  std::ostringstream m;
  rotDeg = o.rotationAngles;
  if (rotDeg.empty())
  {
    const std::string count =
      ValueChecks().within("NumberOfRotations", o.numberOfRotations, 3, kMaxRotationAngles).error();
    if (!count.empty())
    {
      return count;
    }
    for (int k = 0; k < o.numberOfRotations; ++k)
      rotDeg.push_back(k * 180.0 / o.numberOfRotations);
  }
  std::string e =
    checkAngleList("RotationAngles", rotDeg, 0.0, false, 180.0, 3, kMaxRotationAngles);
  if (!e.empty())
    return e;
  tiltDeg = o.tiltAngles;
  if (tiltDeg.empty())
  {
    if (!(o.tiltAngle >= 0.0 && o.tiltAngle < 45.0))
    {
      return mustBe("TiltAngle", o.tiltAngle, "in [0, 45)");
    }
    if (o.tiltAngle > 0.0)
      tiltDeg.push_back(o.tiltAngle);
  }
  else if (!(e = checkAngleList("TiltAngles", tiltDeg, 0.0, true, 45.0, 1, kMaxTiltAngles)).empty())
    return e;
  azDeg = o.tiltAzimuths.empty() ? std::vector<double>{ 0.0, 90.0, 180.0, 270.0 } : o.tiltAzimuths;
  e = checkAngleList("TiltAzimuths", azDeg, 0.0, false, 360.0, 1, kMaxTiltAzimuths);
  if (!e.empty())
    return e;
  if (tiltDeg.size() * azDeg.size() > static_cast<std::size_t>(kMaxTiltedViews))
  {
    m << "TiltAngles (" << tiltDeg.size() << ") x TiltAzimuths (" << azDeg.size()
      << ") gives more than " << kMaxTiltedViews << " views";
    return m.str();
  }
  return {};
}
} // namespace

std::string interpolationFromCode(int code, Interp& interpolation)
{
  return enumFromCode(
    code, 2, "Interpolation", "0 (nearest), 1 (linear) or 2 (Slerp)", interpolation);
}

Status planPLIImage(const FiberModel& model, const PLIOptions& o, PLIPlan& plan)
{
  Status st;
  plan = PLIPlan();
  std::vector<double> rotDeg, tiltDeg, azDeg;
  ValueChecks checks;
  checks.then(checkSectionSizes(o.voxelSize, o.pixelSize))
    .positive("Wavelength", o.wavelength)
    .within("LightIntensity", o.lightIntensity, 0.0, kMaxLightIntensity)
    .positive("StepSize", o.stepSize)
    .atLeast("OpticalSigma", o.opticalSigma, 0.0)
    .require(o.noiseGain == 0.0 || (o.noiseGain >= 1.0 && o.noiseGain <= kMaxNoiseGain),
      "NoiseGain", o.noiseGain, "0 or in [1, " + formatNumber(kMaxNoiseGain) + "]")
    .atLeast("RefractiveIndex", o.refractiveIndex, 1.0)
    .atLeast("NumberOfThreads", o.numberOfThreads, 0)
    .atLeast("tile size", o.tileSize, 1);
  if (checks.error().empty())
    checks.then(polarimeterSetUp(o, rotDeg, tiltDeg, azDeg));
  if (!checks.error().empty())
  {
    st.error = checks.error();
    return st;
  }
  st.error = planSection(model, o.volumeOfInterest, o.voxelSize, o.pixelSize, plan);
  if (!st.ok())
    return st;

  plan.views.push_back(View{ 0.0, 0.0 });
  for (double tilt : tiltDeg)
  {
    const double inTissue = std::asin(std::sin(tilt * kDeg) / o.refractiveIndex); // Snell
    plan.tiltInTissue = std::max(plan.tiltInTissue, inTissue);
    for (double az : azDeg)
    {
      // The tilted sensor sees the section foreshortened by cos τ of the stage tilt (in air).
      const double stretch = o.tiltedSensor ? 1.0 / std::cos(tilt * kDeg) : 1.0;
      plan.views.push_back(View{ inTissue, az * kDeg, stretch });
      plan.tiltDeg.push_back(inTissue / kDeg);
      plan.azimuthDeg.push_back(az);
    }
  }
  plan.rhoDeg = rotDeg;
  for (double r : rotDeg)
    plan.rho.push_back(r * kDeg);

  // The kernel reaches 4σ: wider than the image it only averages the mirrored image with itself,
  // at a cost (and weight vector) growing with σ without bound.
  const double widestSide = static_cast<double>(std::max(plan.pixels[0], plan.pixels[1]));
  if (4.0 * o.opticalSigma > widestSide)
  {
    std::ostringstream m;
    m << "OpticalSigma is " << o.opticalSigma
      << " pixels: the blur kernel (4 sigma) is wider than the image of " << plan.pixels[0] << " x "
      << plan.pixels[1] << " pixels; use at most " << widestSide / 4.0;
    st.error = m.str();
    return st;
  }
  plan.sigmaVox = o.opticalSigma * o.pixelSize / o.voxelSize;
  plan.bytesPerVoxel = kTileBytesPerVoxel;
  plan.estimatedBytes =
    estimatePieceBytes(plan, o, GridRange{ 0, plan.pixels[0], 0, plan.pixels[1] });
  return st;
}

Status planPLITissue(const FiberModel& model, const PLIOptions& o, PLIPlan& plan)
{
  std::vector<int> bundles = o.bundleIds;
  if (bundles.empty())
    for (const Fiber& f : model.fibers)
      bundles.push_back(f.bundle);
  Status st = makeTissueSpec(o.layers, bundles, o.birefringence, o.absorption,
    o.backgroundAbsorption, plan.tissue, o.myelin || hasInnerRadii(model));
  if (!st.ok())
    return st;
  plan.tissue.radius = o.radiusModel;
  const std::string w = resolutionWarning(model, o);
  if (!w.empty())
    st.warnings.push_back(w);
  return st;
}

std::string resolutionWarning(const FiberModel& model, const PLIOptions& o)
{
  double rmin = 0.0;
  bool first = true;
  for (const Fiber& f : model.fibers)
    for (double r : f.radii)
    {
      rmin = first ? r : std::min(rmin, r);
      first = false;
    }
  if (!first && o.voxelSize > 0.5 * rmin)
    return "VoxelSize " + formatNumber(o.voxelSize) + " > half the smallest fiber radius " +
      formatNumber(rmin) + ": layers are not resolved";
  return {};
}

Status planPLI(const FiberModel& model, const PLIOptions& o, PLIPlan& plan)
{
  Status st = planPLIImage(model, o, plan);
  return st.ok() ? planPLITissue(model, o, plan) : st;
}

namespace
{
// Voxel columns that bin into px, grown by R and clipped to the voxel image.
GridRange binnedVoxels(const PLIPlan& plan, const GridRange& px, std::int64_t R)
{
  const GridRange v = voxelColumnsOf(plan, px);
  // The mirror at the global edge only reads inside [0, n); clipping keeps that exact.
  return GridRange{ std::max<std::int64_t>(0, v.i0 - R), std::min(plan.lattice.n[0], v.i1 + R),
    std::max<std::int64_t>(0, v.j0 - R), std::min(plan.lattice.n[1], v.j1 + R) };
}
} // namespace

GridRange voxelColumnsFor(const PLIPlan& plan, const PLIOptions&, const GridRange& px)
{
  return binnedVoxels(plan, px, std::max<std::int64_t>(0, gaussianRadius(plan.sigmaVox)));
}

double estimatePieceBytes(const PLIPlan& plan, const PLIOptions& o, const GridRange& px)
{
  SimParams sp;
  sp.rho = plan.rho;
  sp.threads = o.numberOfThreads;
  sp.tile = o.tileSize;
  sp.interp = o.interpolation;
  const GridRange cols = voxelColumnsFor(plan, o, px);
  double bytes = estimateSimulationBytes(plan.lattice, sp, plan.views, cols);
  // Blur buffers of one view at voxel resolution (x pass, y pass), then the pixel stacks of every
  // view twice: the Core image and the VTK arrays it is copied into.
  const double nrho = static_cast<double>(plan.rho.size());
  bytes += 2.0 * static_cast<double>(cols.nx()) * static_cast<double>(cols.ny()) * nrho * 8.0;
  bytes += 2.0 * static_cast<double>(plan.views.size()) * static_cast<double>(px.nx()) *
    static_cast<double>(px.ny()) * nrho * 8.0;
  return bytes;
}

SimParams simParams(const PLIPlan& plan, const PLIOptions& o)
{
  SimParams sp;
  sp.wavelengthNm = o.wavelength;
  sp.lightIntensity = o.lightIntensity;
  sp.step = o.stepSize;
  sp.rho = plan.rho;
  sp.interp = o.interpolation;
  sp.conv = o.tiltConvention;
  sp.stepRule = o.stepRule;
  sp.lateral = o.lateralOutside;
  sp.tile = o.tileSize;
  sp.threads = o.numberOfThreads;
  return sp;
}

Status runPLI(const FiberModel& model, const PLIOptions& o, GridRange px, PLIImage& image,
  const ProgressFn& progress)
{
  PLIPlan plan;
  Status st = planPLI(model, o, plan);
  if (!st.ok())
  {
    image = PLIImage();
    return st;
  }
  Status run = runPLI(model, o, plan, px, image, progress);
  run.warnings.insert(run.warnings.begin(), st.warnings.begin(), st.warnings.end());
  return run;
}

Status runPLI(const FiberModel& model, const PLIOptions& o, const PLIPlan& planIn, GridRange px,
  PLIImage& image, const ProgressFn& progress)
{
  image = PLIImage();
  image.plan = planIn;
  Status st;
  const PLIPlan& plan = image.plan;
  if (px.nx() <= 0 && px.ny() <= 0 && px.i0 == 0 && px.j0 == 0)
    px = GridRange{ 0, plan.pixels[0], 0, plan.pixels[1] };
  if (px.i0 < 0 || px.j0 < 0 || px.i1 > plan.pixels[0] || px.j1 > plan.pixels[1] || px.nx() < 1 ||
    px.ny() < 1)
  {
    std::ostringstream m;
    m << "pixel range [" << px.i0 << "," << px.i1 << ")x[" << px.j0 << "," << px.j1
      << ") is not inside the image " << plan.pixels[0] << " x " << plan.pixels[1];
    st.error = m.str();
    return st;
  }
  image.range = px;
  const GridRange cols = voxelColumnsFor(plan, o, px);
  // The budget of this piece only: under MPI every rank holds its own columns and pixels, so a
  // job too large for one process may fit split over the ranks.
  std::ostringstream what;
  what << "VoxelSize " << o.voxelSize << " with a VolumeOfInterest of " << plan.lattice.n[0]
       << " x " << plan.lattice.n[1] << " x " << plan.lattice.n[2] << " voxels (" << cols.nx()
       << " x " << cols.ny() << " voxel columns in this piece), " << plan.rho.size()
       << " polarizer angles and " << plan.views.size() << " views";
  st.error = checkMemoryBudget(estimatePieceBytes(plan, o, px), what.str());
  if (!st.ok())
  {
    st.error += ": increase VoxelSize, reduce the volume or split the image over more MPI ranks";
    return st;
  }

  const SimParams sp = simParams(plan, o);
  // Progress: propagation is nearly all of the work.
  ProgressFn simProgress;
  if (progress)
    simProgress = [&progress](double f) { return progress(0.95 * f); };
  std::vector<Stack> voxelStacks;
  SimResult sr =
    simulate(model, plan.tissue, plan.lattice, sp, plan.views, cols, voxelStacks, simProgress);
  st.warnings.insert(st.warnings.end(), sr.status.warnings.begin(), sr.status.warnings.end());
  if (!sr.status.error.empty())
  {
    st.error = sr.status.error;
    return st;
  }
  image.emptySection = sr.emptySection;
  image.fibersOverlap = sr.overlap;
  image.voxeliseCpuSeconds = sr.voxeliseCpuSeconds;
  image.propagateCpuSeconds = sr.propagateCpuSeconds;
  image.raySteps = sr.raySteps;
  image.peakTissueBytes = sr.estimatedBytes;
  if (sr.status.aborted)
  {
    st.aborted = true;
    return st;
  }

  const auto t0 = std::chrono::steady_clock::now();
  const double scale = plan.scale();
  // Blur only the voxels that bin into the pixels (the halo was simulated for the kernel).
  const GridRange needed = binnedVoxels(plan, px, 0);
  for (std::size_t v = 0; v < voxelStacks.size(); ++v)
  {
    Stack blurred, pix;
    Status b = blurStack(
      voxelStacks[v], plan.lattice.n[0], plan.lattice.n[1], plan.sigmaVox, needed, blurred);
    voxelStacks[v] = Stack(); // free the voxel stack early
    if (!b.ok())
    {
      st.error = b.error;
      return st;
    }
    b = binStack(blurred, plan.lattice.n[0], plan.lattice.n[1], scale, px, pix);
    if (!b.ok())
    {
      st.error = b.error;
      return st;
    }
    addNoise(pix, o.noiseGain, o.seed, static_cast<int>(v), plan.pixels[0], o.numberOfThreads);
    image.views.push_back(std::move(pix));
  }
  image.opticsSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  reportProgress(progress, 1.0);
  return st;
}

} // namespace pli
} // namespace fiberpli
