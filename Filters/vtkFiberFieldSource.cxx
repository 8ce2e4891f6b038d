#include "vtkFiberFieldSource.h"

#include "FiberAdapter.h"
#include "FiberCollective.h"
#include "FiberFieldData.h"
#include "FiberPolyData.h"
#include "FiberProgress.h"
#include "Field/FieldFibers.h"
#include "Field/GuideField.h"
#include "GuideLinesData.h"
#include "Model/DataNames.h"
#include "Model/FiberPieces.h"
#include "OrientationFieldData.h"
#include "Util/Random.h"

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <string>

vtkStandardNewMacro(vtkFiberFieldSource);

namespace
{
/// The array name input array `idx` is set to ("" when it is not set by name).
std::string SelectedName(vtkAlgorithm* self, int idx)
{
  vtkInformation* info = self->GetInputArrayInformation(idx);
  return info && info->Has(vtkDataObject::FIELD_NAME()) ? info->Get(vtkDataObject::FIELD_NAME())
                                                        : "";
}

/// ParaView's array list offers "None" first for the optional second field.
bool IsNone(const std::string& name)
{
  return name.empty() || name == "None";
}

/// The input arrays OrientationArray and SecondOrientationArray selected: array, association.
struct SelectedArray
{
  vtkDataArray* array = nullptr;
  int association = vtkDataObject::FIELD_ASSOCIATION_POINTS;
};

/// The field(s) of the image's OrientationArray and SecondOrientationArray: "" or the message.
/// `notFinite` receives how many axes were NaN or infinite.
std::string ImageFields(vtkAlgorithm* self, vtkImageData* image, const SelectedArray selected[2],
  std::vector<fiberpli::OrientationField>& fields, std::size_t& notFinite)
{
  if (!image || image->GetNumberOfPoints() == 0)
  {
    return "the input image has no points (an orientation field needs a 3-D grid; or give guide "
           "lines as a vtkPolyData)";
  }
  // The arrays: the first is required, the second optional ("None"); a 6-component first array
  // holds both populations.
  notFinite = 0;
  int firstAssociation = -1;
  std::string firstName;
  for (int idx = 0; idx < 2; ++idx)
  {
    const std::string name = SelectedName(self, idx);
    const std::string property = idx == 0 ? "OrientationArray '" : "SecondOrientationArray '";
    const int association = selected[idx].association;
    vtkDataArray* vectors = selected[idx].array;
    if (!vectors && idx == 1 && IsNone(name))
    {
      break;
    }
    if (!vectors)
    {
      return property + name +
        "': the input has no such array (a point or cell array of 3 components, or 6 for two axes "
        "per point, is needed)";
    }
    const bool cells = association == vtkDataObject::FIELD_ASSOCIATION_CELLS;
    if (idx == 1 && fields.size() == 2)
    {
      return property + name + "' is set, but OrientationArray '" + firstName +
        "' has 6 components and already holds two populations (at most two): set "
        "SecondOrientationArray to None";
    }
    if (idx == 1 && vectors->GetNumberOfComponents() != 3)
    {
      return property + name + "' has " + std::to_string(vectors->GetNumberOfComponents()) +
        " components, must have 3 (two axes per point go into OrientationArray as one "
        "6-component array)";
    }
    if (idx == 1 && association != firstAssociation)
    {
      return property + name + "' is a " + (cells ? "cell" : "point") +
        " array and OrientationArray is not: both fields must be on the same grid";
    }
    firstAssociation = association;
    firstName = name;
    std::size_t bad = 0;
    const std::string problem = fiberpli::ToOrientationFields(image, vectors, cells, fields, bad);
    if (!problem.empty())
    {
      return property + name + "': " + problem;
    }
    notFinite += bad;
  }
  return {};
}
} // namespace

//------------------------------------------------------------------------------
// Construct with the point array "orientation" as the field, no second field, VolumeFraction 0.3,
// radius 0.8 µm, segment length 2 µm, RK4, seed 42.
vtkFiberFieldSource::vtkFiberFieldSource()
{
  this->SetNumberOfInputPorts(1);
  this->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "orientation");
  this->SetInputArrayToProcess(1, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "None");
}

//------------------------------------------------------------------------------
int vtkFiberFieldSource::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData"); // guide lines
  return 1;
}

//------------------------------------------------------------------------------
// Every piece traces from the whole field or all guides (a fiber crosses the whole region).
int vtkFiberFieldSource::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  if (inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(),
      inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()), 6);
  }
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), 0);
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), 1);
  return 1;
}

//------------------------------------------------------------------------------
int vtkFiberFieldSource::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // Under MPI all ranks fail together; an exception becomes an error (FiberCollective.h,
  // FiberGuard.h).
  return fiberpli::FiberCollective::RunCollectively(this, request, outputVector, "FiberFieldSource",
    [&] { return this->Execute(inputVector, outputVector); });
}

//------------------------------------------------------------------------------
int vtkFiberFieldSource::Execute(
  vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  const fiberpli::AbortScope abortScope(this); // an abort applies to this execution only
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  output->Initialize();
  const int piece = fiberpli::FiberPolyData::RequestedPiece(outInfo);
  const int pieces = fiberpli::FiberPolyData::RequestedPieces(outInfo);
  const std::string badSeed = fiberpli::validateSeed(this->Seed);
  if (!badSeed.empty())
  {
    vtkErrorMacro(<< "FiberFieldSource: " << badSeed);
    return 0;
  }
  fiberpli::FieldFiberOptions options;
  options.volumeFraction = this->VolumeFraction;
  options.numberOfFibers = this->NumberOfFibers;
  options.fiberRadius = this->FiberRadius;
  options.radiusSpread = this->RadiusSpread;
  options.trace.segmentLength = this->SegmentLength;
  options.trace.scheme = static_cast<fiberpli::TraceScheme>(this->IntegrationScheme);
  options.trace.maxLength = this->MaxFiberLength;
  options.seed = static_cast<std::uint64_t>(this->Seed);
  options.seedCandidates = this->SeedCandidates;
  options.populationShares.assign(this->PopulationShares, this->PopulationShares + 2);
  options.realism.beadingCV = this->BeadingCV;
  options.realism.beadingLength = this->BeadingLength;
  options.realism.gRatio = this->GRatio;
  std::string code =
    fiberpli::radiusDistributionFromCode(this->RadiusDistribution, options.radiusDistribution);
  if (code.empty())
  {
    code = fiberpli::gRatioModelFromCode(this->GRatioModel, options.realism.gRatioModel);
  }
  if (!code.empty())
  {
    vtkErrorMacro(<< "FiberFieldSource: " << code);
    return 0;
  }
  // The fields: from the image's arrays, or rasterised from guide lines.
  std::vector<fiberpli::OrientationField> fields;
  double traceBegin = 0.0;
  if (!fiberpli::CheckThreads(this, this->NumberOfThreads))
  {
    return 0;
  }
  options.threads = fiberpli::resolveThreadCount(this->NumberOfThreads);
  if (vtkPolyData* guides = vtkPolyData::GetData(inputVector[0]))
  {
    fiberpli::GuideFieldOptions guideOptions;
    guideOptions.radius = this->GuideRadius;
    guideOptions.spacing = this->GuideSpacing;
    guideOptions.threads = this->NumberOfThreads;
    if (!fiberpli::CheckEnum(this, this->GuidePopulations, 1, "GuidePopulations",
          "0 (One) or 1 (ByBundle)", guideOptions.populations))
    {
      return 0;
    }
    std::vector<fiberpli::GuideLine> lines;
    std::string problem = fiberpli::ToGuideLines(guides, lines);
    fiberpli::GuideFieldResult guideField;
    if (problem.empty())
    {
      traceBegin = 0.2;
      guideField = fiberpli::guideOrientationFields(
        lines, guideOptions, fiberpli::MakeProgress(this, 0.0, traceBegin));
      if (guideField.aborted)
      {
        return 1; // an aborted source passes nothing on (AbortScope empties the output)
      }
      problem = guideField.error;
    }
    if (!problem.empty())
    {
      vtkErrorMacro(<< "FiberFieldSource: " << problem);
      return 0;
    }
    fields = std::move(guideField.fields);
  }
  else
  {
    vtkImageData* image = vtkImageData::GetData(inputVector[0]);
    SelectedArray selected[2];
    for (int idx = 0; idx < 2 && image; ++idx)
    {
      selected[idx].array = this->GetInputArrayToProcess(idx, image, selected[idx].association);
    }
    std::size_t notFinite = 0;
    const std::string problem = ImageFields(this, image, selected, fields, notFinite);
    if (!problem.empty())
    {
      vtkErrorMacro(<< "FiberFieldSource: " << problem);
      return 0;
    }
    if (notFinite > 0)
    {
      vtkWarningMacro(
        << "FiberFieldSource: " << notFinite
        << " orientation vector(s) are NaN or infinite; they count as empty (no fibers there)");
    }
  }
  std::vector<const fiberpli::OrientationField*> pointers;
  for (const fiberpli::OrientationField& f : fields)
  {
    pointers.push_back(&f);
  }

  this->UpdateProgress(traceBegin);
  fiberpli::FieldFiberResult result =
    fiberpli::generateFieldFibers(pointers, options, fiberpli::MakeProgress(this, traceBegin, 0.9));
  if (result.aborted)
  {
    return 1; // an aborted source passes nothing on (AbortScope empties the output)
  }
  if (!result.error.empty())
  {
    vtkErrorMacro(<< "FiberFieldSource: " << result.error);
    return 0;
  }
  for (const std::string& w : result.warnings)
  {
    vtkWarningMacro(<< "FiberFieldSource: " << w);
  }
  // This piece's share of the global fiber order (ids stay global).
  const fiberpli::FiberRange range =
    fiberpli::pieceRange(result.model.fibers.size(), piece, pieces);
  fiberpli::FiberModel mine;
  mine.fibers.assign(
    std::make_move_iterator(result.model.fibers.begin() + static_cast<std::ptrdiff_t>(range.begin)),
    std::make_move_iterator(result.model.fibers.begin() + static_cast<std::ptrdiff_t>(range.end)));
  fiberpli::FiberPolyData::FromSourceModel(mine, output, this->SegmentLength, this->Seed);
  fiberpli::AddFieldDoubles(
    output, fiberpli::fiberfield::kTracedVolumeFraction, { result.volumeFraction });
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkFiberFieldSource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "VolumeFraction: " << this->VolumeFraction << "\n";
  os << indent << "NumberOfFibers: " << this->NumberOfFibers << "\n";
  os << indent << "FiberRadius: " << this->FiberRadius << "\n";
  os << indent << "RadiusSpread: " << this->RadiusSpread << "\n";
  os << indent << "RadiusDistribution: " << this->RadiusDistribution << "\n";
  os << indent << "SegmentLength: " << this->SegmentLength << "\n";
  os << indent << "IntegrationScheme: " << this->IntegrationScheme << "\n";
  os << indent << "MaxFiberLength: " << this->MaxFiberLength << "\n";
  os << indent << "PopulationShares: " << this->PopulationShares[0] << " "
     << this->PopulationShares[1] << "\n";
  os << indent << "BeadingCV: " << this->BeadingCV << "\n";
  os << indent << "BeadingLength: " << this->BeadingLength << "\n";
  os << indent << "GRatio: " << this->GRatio << "\n";
  os << indent << "GRatioModel: " << this->GRatioModel << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "SeedCandidates: " << this->SeedCandidates << "\n";
  os << indent << "GuideRadius: " << this->GuideRadius << "\n";
  os << indent << "GuideSpacing: " << this->GuideSpacing << "\n";
  os << indent << "GuidePopulations: " << this->GuidePopulations << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
}
