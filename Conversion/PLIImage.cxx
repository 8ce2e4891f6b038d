#include "PLIImage.h"

#include "Analysis/PliStackRules.h"
#include "ArrayValues.h"
#include "FiberFieldData.h"
#include "Model/DataNames.h"
#include "Section/TiltConvention.h"

#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>

#include <algorithm>
#include <cmath>

namespace fiberpli
{
namespace
{
// The analysis and the ground truth have always converted with these two (bit-wise different)
// factors; both are kept so that their maps stay bit-identical.
constexpr double kDeg = 3.14159265358979323846 / 180.0;
constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;

void AddPieceFibers(vtkImageData* output, const PieceFibers& fibers)
{
  AddFieldDoubles(output, plifield::kTileFibers, { fibers.tile });
  AddFieldDoubles(output, plifield::kModelFibers, { fibers.model });
}

/// The raw values of the image that PliStackRules decides on.
PliStackFields StackFields(vtkImageData* image)
{
  PliStackFields f;
  int ext[6];
  image->GetExtent(ext);
  f.slices = static_cast<std::int64_t>(ext[5]) - ext[4] + 1;
  vtkDataArray* intensity = image->GetPointData()->GetArray(plifield::kIntensity);
  f.hasIntensity = intensity != nullptr;
  f.components = intensity ? intensity->GetNumberOfComponents() : 0;
  for (std::size_t v = 0;; ++v)
  {
    vtkDataArray* a = image->GetPointData()->GetArray(plifield::intensityTilt(v).c_str());
    if (!a)
    {
      break;
    }
    f.tiltComponents.push_back(a->GetNumberOfComponents());
  }
  f.hasPolarizerAngles = FieldArray(image, plifield::kPolarizerAngles) != nullptr;
  f.polarizerAngles = FieldValues(image, plifield::kPolarizerAngles);
  f.hasTiltAngles = FieldArray(image, plifield::kTiltAngles) != nullptr;
  f.tiltAngles = FieldValues(image, plifield::kTiltAngles);
  f.tiltDirections = FieldValues(image, plifield::kTiltDirections);
  f.tiltAngle = FieldValue(image, plifield::kTiltAngle, 0.0);
  f.tiltConvention = FieldValue(image, plifield::kTiltConvention, 0.0);
  f.tiltedSensor = FieldValue(image, plifield::kTiltedSensor, 0.0);
  f.noiseGain = FieldValue(image, plifield::kNoiseGain, -1.0);
  return f;
}

} // namespace

//------------------------------------------------------------------------------
void WritePliStack(const pli::PLIImage& image, const pli::PLIPlan& plan,
  const pli::PLIOptions& options, const PieceFibers& fibers, vtkImageData* output)
{
  const int nrho = static_cast<int>(plan.rho.size());
  const vtkIdType n = static_cast<vtkIdType>(image.range.count());
  for (std::size_t v = 0; v < image.views.size(); ++v)
  {
    const std::string name = v == 0 ? plifield::kIntensity : plifield::intensityTilt(v - 1);
    vtkNew<vtkDoubleArray> a;
    a->SetName(name.c_str());
    a->SetNumberOfComponents(nrho);
    a->SetNumberOfTuples(n);
    std::copy(image.views[v].data.begin(), image.views[v].data.end(), a->GetPointer(0));
    output->GetPointData()->AddArray(a);
  }
  output->GetPointData()->SetActiveScalars(plifield::kIntensity);

  AddFieldDoubles(output, plifield::kPolarizerAngles, plan.rhoDeg);
  AddFieldDoubles(output, plifield::kTiltAngle, { plan.tiltInTissue * 180.0 / M_PI });
  AddFieldDoubles(output, plifield::kTiltAngles, plan.tiltDeg);
  AddFieldDoubles(output, plifield::kTiltDirections, plan.azimuthDeg);
  AddFieldDoubles(output, plifield::kSectionThickness, { plan.thickness });
  AddFieldDoubles(output, plifield::kWavelength, { options.wavelength });
  AddFieldInt(output, plifield::kTiltConvention, tiltConventionCode(options.tiltConvention));
  AddFieldInt(output, plifield::kTiltedSensor, options.tiltedSensor ? 1 : 0);
  AddFieldDoubles(output, plifield::kNoiseGain, { options.noiseGain });
  AddFieldInt(output, plifield::kEmptySection, image.emptySection ? 1 : 0);
  AddFieldDoubles(output, plifield::kVoxelSize, { options.voxelSize });
  AddFieldDoubles(output, plifield::kPixelSize, { options.pixelSize });
  AddFieldDoubles(output, plifield::kLightIntensity, { options.lightIntensity });
  AddPieceFibers(output, fibers);
}

//------------------------------------------------------------------------------
void WritePliTissue(const pli::TissueVolume& tissue, const pli::PLIPlan& plan,
  const PieceFibers& fibers, vtkImageData* output)
{
  const vtkIdType n = static_cast<vtkIdType>(tissue.label.size());
  vtkNew<vtkIntArray> label;
  label->SetName(plifield::kLabel);
  label->SetNumberOfValues(n);
  std::copy(tissue.label.begin(), tissue.label.end(), label->GetPointer(0));
  vtkNew<vtkFloatArray> axis;
  axis->SetName(plifield::kOpticAxis);
  axis->SetNumberOfComponents(3);
  axis->SetNumberOfTuples(n);
  std::copy(tissue.axis.begin(), tissue.axis.end(), axis->GetPointer(0));
  output->GetPointData()->AddArray(label);
  output->GetPointData()->AddArray(axis);
  output->GetPointData()->SetActiveScalars(plifield::kLabel);
  // What a label means: 1 + b·L + l for layer l of the b-th bundle id; 0 = embedding medium.
  const std::vector<double> bundles(plan.tissue.bundleIds.begin(), plan.tissue.bundleIds.end());
  AddFieldDoubles(output, plifield::kLabelBundleIds, bundles);
  AddFieldInt(output, plifield::kLayersPerBundle, plan.tissue.maxLayers());
  AddFieldDoubles(output, plifield::kVoxelSize, { plan.lattice.voxel });
  AddPieceFibers(output, fibers);
}

//------------------------------------------------------------------------------
std::string ReadPliStack(vtkImageData* image, InclinationMethod method, PliStackInput& input)
{
  input = PliStackInput();
  PliStackLayout layout;
  const std::string error = decodePliStack(StackFields(image), method, layout);
  if (!error.empty())
  {
    return error;
  }
  int ext[6];
  image->GetExtent(ext);
  PliStack& stack = input.stack;
  stack.nx = ext[1] - ext[0] + 1;
  stack.ny = ext[3] - ext[2] + 1;
  stack.rho = layout.rho;
  input.copies.emplace_back();
  stack.intensity =
    AsDoubles(image->GetPointData()->GetArray(plifield::kIntensity), input.copies.back());
  for (std::size_t v = 0; v < layout.tiltStacks; ++v)
  {
    input.copies.emplace_back();
    stack.tilts.push_back(AsDoubles(
      image->GetPointData()->GetArray(plifield::intensityTilt(v).c_str()), input.copies.back()));
  }
  stack.tiltViews = layout.tiltViews;
  stack.convention = layout.convention;
  stack.noiseGain = layout.noiseGain;
  return {};
}

//------------------------------------------------------------------------------
void AddCroppedMap(vtkImageData* output, const char* name, const std::vector<double>& map,
  std::int64_t nx, const GridRange& range, double scale)
{
  if (map.empty())
  {
    return;
  }
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->SetNumberOfValues(static_cast<vtkIdType>(range.count()));
  vtkIdType k = 0;
  for (std::int64_t j = range.j0; j < range.j1; ++j)
  {
    for (std::int64_t i = range.i0; i < range.i1; ++i)
    {
      a->SetValue(k++, map[static_cast<std::size_t>(i + nx * j)] * scale);
    }
  }
  output->GetPointData()->AddArray(a);
}

//------------------------------------------------------------------------------
void WriteAnalysisMaps(
  const PliAnalysisMaps& maps, std::int64_t nx, const GridRange& range, vtkImageData* output)
{
  AddCroppedMap(output, plifield::kTransmittance, maps.transmittance, nx, range, 1.0);
  AddCroppedMap(output, plifield::kDirection, maps.direction, nx, range, 1.0 / kDeg);
  AddCroppedMap(output, plifield::kRetardation, maps.retardation, nx, range, 1.0);
  AddCroppedMap(output, plifield::kInclination, maps.inclination, nx, range, 1.0 / kDeg);
  AddCroppedMap(
    output, plifield::kInclinationSigned, maps.inclinationSigned, nx, range, 1.0 / kDeg);
  AddCroppedMap(output, plifield::kRelativeThickness, maps.relativeThickness, nx, range, 1.0);
  AddCroppedMap(output, plifield::kFitChi2, maps.chi2, nx, range, 1.0);
  output->GetPointData()->SetActiveScalars(plifield::kDirection);
  // Directions just below 180° can round to exactly 180 in degrees: keep the [0, 180) contract.
  if (auto* direction =
        vtkDoubleArray::SafeDownCast(output->GetPointData()->GetArray(plifield::kDirection)))
  {
    for (vtkIdType k = 0; k < direction->GetNumberOfValues(); ++k)
    {
      if (direction->GetValue(k) >= 180.0)
      {
        direction->SetValue(k, direction->GetValue(k) - 180.0);
      }
    }
  }
  AddFieldDoubles(output, plifield::kReferenceRetardation, { maps.referenceRetardation });
  AddFieldInt(output, plifield::kInclinationMethod, static_cast<int>(maps.method));
}

//------------------------------------------------------------------------------
void WriteGroundTruthMaps(const GroundTruthMaps& maps, std::int64_t nx, const GridRange& range,
  const PieceFibers& fibers, vtkImageData* output)
{
  AddCroppedMap(output, plifield::kDirection, maps.direction, nx, range, kRadToDeg);
  AddCroppedMap(output, plifield::kInclination, maps.inclination, nx, range, kRadToDeg);
  AddCroppedMap(output, plifield::kInclinationSigned, maps.inclinationSigned, nx, range, kRadToDeg);
  AddCroppedMap(output, plifield::kFraction, maps.fraction, nx, range, 1.0);
  AddCroppedMap(output, plifield::kAnisotropy, maps.anisotropy, nx, range, 1.0);
  output->GetPointData()->SetActiveScalars(plifield::kDirection);
  AddPieceFibers(output, fibers);
}

} // namespace fiberpli
