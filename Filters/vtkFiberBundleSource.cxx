#include "vtkFiberBundleSource.h"

#include "FiberAdapter.h"
#include "FiberCollective.h"
#include "FiberPolyData.h"
#include "FiberProgress.h"
#include "FiberRealism.h"
#include "Model/DataNames.h"
#include "Tissue/BundleGenerator.h"
#include "Tissue/Myelin.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkDataArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <cstdint>
#include <vector>

vtkStandardNewMacro(vtkFiberBundleSource);

//------------------------------------------------------------------------------
// Construct a Cylinder of radius 10 µm and length 60 µm, fiber radius 0.8 µm (spread 0,
// LogNormal) on a 2 µm triangular grid, segment length 2 µm, displacement 0.2 µm, crossing angle
// 90°, uncrossed fraction 0.25, Ranvier spacing -1 (shape default) / depth 0.3 / length 1 µm,
// seed 42. Input port 0 (the trajectory polyline) is optional.
vtkFiberBundleSource::vtkFiberBundleSource()
{
  this->SetNumberOfInputPorts(1);
}

//------------------------------------------------------------------------------
int vtkFiberBundleSource::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

//------------------------------------------------------------------------------
// The trajectory is small and needed whole: ask for all of it whatever piece is requested here.
int vtkFiberBundleSource::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  if (inputVector[0]->GetNumberOfInformationObjects() > 0)
  {
    fiberpli::FiberPolyData::RequestAllFibers(inputVector[0]->GetInformationObject(0));
  }
  return 1;
}

//------------------------------------------------------------------------------
// Every piece makes its own fibers (docs/tissue-models.md §9).
int vtkFiberBundleSource::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  outputVector->GetInformationObject(0)->Set(vtkAlgorithm::CAN_HANDLE_PIECE_REQUEST(), 1);
  return 1;
}

//------------------------------------------------------------------------------
int vtkFiberBundleSource::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // Under MPI all ranks fail together (FiberCollective.h), e.g. when one rank's memory budget is
  // lower.
  return fiberpli::FiberCollective::RunCollectively(this, request, outputVector,
    fiberpli::ProxyName(this), [&] { return this->ExecutePiece(inputVector, outputVector); });
}

//------------------------------------------------------------------------------
int vtkFiberBundleSource::ExecutePiece(
  vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  const fiberpli::AbortScope abortScope(this); // an abort applies to this execution only
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  output->Initialize();
  const int piece = fiberpli::FiberPolyData::RequestedPiece(outInfo);
  const int pieces = fiberpli::FiberPolyData::RequestedPieces(outInfo);

  if (!fiberpli::CheckSeed(this, this->Seed))
  {
    return 0;
  }
  fiberpli::BundleOptions options;
  options.bundleRadius = this->BundleRadius;
  options.length = this->Length;
  options.fiberRadius = this->FiberRadius;
  options.radiusSpread = this->RadiusSpread;
  options.fiberSpacing = this->FiberSpacing;
  options.numberOfFibers = this->NumberOfFibers;
  options.segmentLength = this->SegmentLength;
  options.displacement = this->Displacement;
  options.crossingAngle = this->CrossingAngle;
  options.uncrossedFraction = this->UncrossedFraction;
  options.ranvierSpacing = this->RanvierSpacing;
  options.ranvierDepth = this->RanvierDepth;
  options.ranvierLength = this->RanvierLength;
  options.seed = static_cast<std::uint64_t>(this->Seed);
  // The enumerated properties in the order validateBundleOptions names them.
  std::string code = fiberpli::bundleShapeFromCode(this->Shape, options.shape);
  if (code.empty())
  {
    code =
      fiberpli::radiusDistributionFromCode(this->RadiusDistribution, options.radiusDistribution);
  }
  if (code.empty())
  {
    code = fiberpli::RealismKnobs(this, options.realism);
  }
  if (!code.empty())
  {
    fiberpliErrorMacro(<< code);
    return 0;
  }

  std::vector<fiberpli::Vec3> trajectory;
  std::vector<double> scale;
  bool hasScale = false;
  if (this->Shape == TRAJECTORY)
  {
    vtkPolyData* input = inputVector[0]->GetNumberOfInformationObjects() > 0
      ? vtkPolyData::GetData(inputVector[0])
      : nullptr;
    if (!input)
    {
      fiberpliErrorMacro(<< "Shape is Trajectory but no polyline is connected to input port 0 "
                            "(Trajectory); connect one or choose another Shape");
      return 0;
    }
    if (fiberpli::FiberPolyData::IsEmpty(input))
    {
      return 1; // an empty trajectory makes an empty bundle, not an error
    }
    if (!input->GetLines() || input->GetLines()->GetNumberOfCells() == 0)
    {
      fiberpliErrorMacro(<< "the Trajectory input has no line cell (polyline)");
      return 0;
    }
    vtkDataArray* scaleArray =
      input->GetPointData()->GetArray(fiberpli::fiberfield::kTrajectoryScale);
    if (scaleArray && scaleArray->GetNumberOfComponents() != 1)
    {
      fiberpliErrorMacro(<< "the Trajectory point array 'scale' has "
                         << scaleArray->GetNumberOfComponents() << " components, must have 1");
      return 0;
    }
    if (scaleArray && scaleArray->GetNumberOfTuples() != input->GetNumberOfPoints())
    {
      fiberpliErrorMacro(<< "the Trajectory point array 'scale' has "
                         << scaleArray->GetNumberOfTuples() << " values for "
                         << input->GetNumberOfPoints() << " points");
      return 0;
    }
    auto it = vtk::TakeSmartPointer(input->GetLines()->NewIterator());
    it->GoToFirstCell();
    vtkIdType n = 0;
    const vtkIdType* ids = nullptr;
    it->GetCurrentCell(n, ids);
    for (vtkIdType i = 0; i < n; ++i)
    {
      if (ids[i] < 0 || ids[i] >= input->GetNumberOfPoints())
      {
        fiberpliErrorMacro(<< "the Trajectory line refers to point " << ids[i]
                           << ", but the input has " << input->GetNumberOfPoints() << " points");
        return 0;
      }
      double p[3];
      input->GetPoint(ids[i], p);
      trajectory.push_back({ p[0], p[1], p[2] });
      if (scaleArray)
      {
        scale.push_back(scaleArray->GetTuple1(ids[i]));
      }
    }
    hasScale = scaleArray != nullptr;
  }
  const std::vector<fiberpli::Vec3>* path = this->Shape == TRAJECTORY ? &trajectory : nullptr;
  const std::vector<double>* sigma = hasScale ? &scale : nullptr;

  const std::string invalid = fiberpli::validateBundleOptions(options, path, sigma, pieces);
  if (!invalid.empty())
  {
    fiberpliErrorMacro(<< invalid);
    return 0;
  }
  const std::string warning = fiberpli::bundleWarnings(options, path, sigma);
  if (!warning.empty() && piece == 0) // once, not once per rank
  {
    fiberpliWarningMacro(<< warning);
  }

  const fiberpli::ProgressFn progress = fiberpli::MakeProgress(this);
  progress(0.0);
  fiberpli::FiberModel model = fiberpli::generateBundle(options, path, sigma, piece, pieces);
  if (!progress(0.8))
  {
    return 1; // aborted: no partial model is passed on
  }
  fiberpli::addMyelin(model, options.realism); // inner radii with myelin on
  fiberpli::FiberPolyData::FromSourceModel(model, output, this->SegmentLength, this->Seed);
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkFiberBundleSource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Shape: " << this->Shape << "\n";
  os << indent << "BundleRadius: " << this->BundleRadius << "\n";
  os << indent << "Length: " << this->Length << "\n";
  os << indent << "FiberRadius: " << this->FiberRadius << "\n";
  os << indent << "RadiusSpread: " << this->RadiusSpread << "\n";
  os << indent << "RadiusDistribution: " << this->RadiusDistribution << "\n";
  os << indent << "FiberSpacing: " << this->FiberSpacing << "\n";
  os << indent << "NumberOfFibers: " << this->NumberOfFibers << "\n";
  os << indent << "SegmentLength: " << this->SegmentLength << "\n";
  os << indent << "Displacement: " << this->Displacement << "\n";
  os << indent << "CrossingAngle: " << this->CrossingAngle << "\n";
  os << indent << "UncrossedFraction: " << this->UncrossedFraction << "\n";
  os << indent << "RanvierSpacing: " << this->RanvierSpacing << "\n";
  os << indent << "RanvierDepth: " << this->RanvierDepth << "\n";
  os << indent << "RanvierLength: " << this->RanvierLength << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "Tortuosity: " << this->Tortuosity << "\n";
  os << indent << "UndulationWavelength: " << this->UndulationWavelength << "\n";
  os << indent << "DispersionC2: " << this->DispersionC2 << "\n";
  os << indent << "BeadingCV: " << this->BeadingCV << "\n";
  os << indent << "BeadingLength: " << this->BeadingLength << "\n";
  os << indent << "GRatio: " << this->GRatio << "\n";
  os << indent << "GRatioModel: " << this->GRatioModel << "\n";
}
