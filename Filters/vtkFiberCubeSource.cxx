#include "vtkFiberCubeSource.h"

#include "FiberAdapter.h"
#include "FiberCollective.h"
#include "FiberFieldData.h"
#include "FiberPolyData.h"
#include "FiberProgress.h"
#include "FiberRealism.h"
#include "Tissue/CubeGenerator.h"
#include "Tissue/Myelin.h"

#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>

#include <cmath>

vtkStandardNewMacro(vtkFiberCubeSource);

namespace
{
// What the cell allowed of the requested shape: the axes taken (with a crossing angle) and the
// dispersion reached (with dispersion), and a warning (once, on piece 0) where it falls short.
void AddRealismFieldData(
  vtkFiberCubeSource* self, vtkPolyData* output, const fiberpli::CubeOptions& options, int piece)
{
  const std::vector<fiberpli::PopulationAxis> axes = fiberpli::cubePopulationAxes(options);
  if (options.crossingAngle != 90.0 && axes.size() >= 2)
  {
    std::vector<double> values;
    for (const fiberpli::PopulationAxis& a : axes)
    {
      values.insert(values.end(), { a.direction.x, a.direction.y, a.direction.z });
    }
    fiberpli::AddFieldDoubles(output, fiberpli::fiberfield::kPopulationAxes, values);
    const double achieved = fiberpli::axesAngle(axes);
    if (std::fabs(achieved - options.crossingAngle) > 1.0 && piece == 0)
    {
      vtkWarningWithObjectMacro(
        self, << fiberpli::ProxyName(self) << ": CrossingAngle " << options.crossingAngle
              << ": the nearest lattice direction of the periodic cell is (" << axes[1].lattice.x
              << ", " << axes[1].lattice.y << ", 0), " << achieved << " degrees from population 0");
    }
  }
  if (options.realism.dispersed())
  {
    const std::vector<double> c2 = fiberpli::cubeDispersionC2(options);
    fiberpli::AddFieldDoubles(output, fiberpli::fiberfield::kDispersionC2, c2);
    for (std::size_t k = 0; k < c2.size() && piece == 0; ++k)
    {
      if (std::fabs(c2[k] - options.realism.dispersionC2) > 0.02)
      {
        vtkWarningWithObjectMacro(
          self, << fiberpli::ProxyName(self) << ": DispersionC2 " << options.realism.dispersionC2
                << ": population " << k << " reaches " << c2[k]
                << (options.periodic ? " with the lattice directions of the periodic cell" : "")
                << " (field data dispersion_c2)");
      }
    }
  }
}

} // namespace

//------------------------------------------------------------------------------
// Construct with 1 population of 1000 fibers in a cube of edge √3·30 µm, radius 0.8 µm,
// segment length 2 µm, displacement 0.5 µm, seed 42.
vtkFiberCubeSource::vtkFiberCubeSource()
{
  this->SetNumberOfInputPorts(0);
}

//------------------------------------------------------------------------------
// Every piece makes its own fibers (docs/tissue-models.md §9), so VTK executes it for any piece.
int vtkFiberCubeSource::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  outputVector->GetInformationObject(0)->Set(vtkAlgorithm::CAN_HANDLE_PIECE_REQUEST(), 1);
  return 1;
}

//------------------------------------------------------------------------------
int vtkFiberCubeSource::RequestData(
  vtkInformation* request, vtkInformationVector**, vtkInformationVector* outputVector)
{
  // Under MPI all ranks fail together (FiberCollective.h), e.g. when one rank's memory budget is
  // lower.
  return fiberpli::FiberCollective::RunCollectively(this, request, outputVector,
    fiberpli::ProxyName(this), [&] { return this->ExecutePiece(outputVector); });
}

//------------------------------------------------------------------------------
int vtkFiberCubeSource::ExecutePiece(vtkInformationVector* outputVector)
{
  const fiberpli::AbortScope abortScope(this); // an abort applies to this execution only
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  const int piece = fiberpli::FiberPolyData::RequestedPiece(outInfo);
  const int pieces = fiberpli::FiberPolyData::RequestedPieces(outInfo);

  if (!fiberpli::CheckSeed(this, this->Seed))
  {
    return 0;
  }
  fiberpli::CubeOptions options;
  options.populations = this->Populations;
  options.numberOfFibers = this->NumberOfFibers;
  options.edgeLength = this->EdgeLength;
  options.fiberRadius = this->FiberRadius;
  options.segmentLength = this->SegmentLength;
  options.displacement = this->Displacement;
  options.seed = static_cast<std::uint64_t>(this->Seed);
  options.crossingAngle = this->CrossingAngle;
  options.undulationCoherence = this->UndulationCoherence;
  options.beadPhasing = this->BeadPhasing;
  options.populationShares.assign(this->PopulationShares, this->PopulationShares + 3);
  options.radiusSpread = this->RadiusSpread;
  options.periodic = this->Periodic;
  options.volumeFraction = this->VolumeFraction;
  // The enumerated properties in the order validateCubeOptions names them.
  std::string invalid =
    fiberpli::radiusDistributionFromCode(this->RadiusDistribution, options.radiusDistribution);
  if (invalid.empty())
  {
    invalid = fiberpli::cubeSeedingFromCode(this->Seeding, options.seeding);
  }
  if (invalid.empty())
  {
    invalid = fiberpli::RealismKnobs(this, options.realism);
  }
  if (invalid.empty())
  {
    invalid = fiberpli::cubeArrangementFromCode(this->Arrangement, options.arrangement);
  }
  if (invalid.empty())
  {
    invalid = fiberpli::validateCubeOptions(options, pieces);
  }
  if (!invalid.empty())
  {
    fiberpliErrorMacro(<< invalid);
    return 0;
  }

  this->UpdateProgress(0.0);
  std::string warning;
  bool aborted = false;
  // Progress and abort over the polydisperse Lattice seeding's disk packing and the fibers' points.
  const fiberpli::ProgressFn progress = fiberpli::MakeProgress(this, 0.0, 0.7);
  fiberpli::FiberModel model = fiberpli::generateCube(options, piece, pieces, &warning,
    [&](double f)
    {
      aborted = !progress(f);
      return !aborted;
    });
  if (aborted)
  {
    return 1; // an aborted source passes nothing on (AbortScope marks the output)
  }
  if (!warning.empty())
  {
    fiberpliWarningMacro(<< warning);
  }
  this->UpdateProgress(0.8);
  fiberpli::addMyelin(model, options.realism); // inner radii with myelin on
  fiberpli::FiberPolyData::FromSourceModel(model, output, this->SegmentLength, this->Seed);
  if (this->Periodic)
  {
    fiberpli::AddPeriodicCell(output, fiberpli::cubeCell(options));
  }
  AddRealismFieldData(this, output, options, piece);
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkFiberCubeSource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Populations: " << this->Populations << "\n";
  os << indent << "NumberOfFibers: " << this->NumberOfFibers << "\n";
  os << indent << "EdgeLength: " << this->EdgeLength << "\n";
  os << indent << "FiberRadius: " << this->FiberRadius << "\n";
  os << indent << "SegmentLength: " << this->SegmentLength << "\n";
  os << indent << "Displacement: " << this->Displacement << "\n";
  os << indent << "RadiusSpread: " << this->RadiusSpread << "\n";
  os << indent << "RadiusDistribution: " << this->RadiusDistribution << "\n";
  os << indent << "Periodic: " << this->Periodic << "\n";
  os << indent << "VolumeFraction: " << this->VolumeFraction << "\n";
  os << indent << "Seeding: " << this->Seeding << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "Tortuosity: " << this->Tortuosity << "\n";
  os << indent << "UndulationWavelength: " << this->UndulationWavelength << "\n";
  os << indent << "DispersionC2: " << this->DispersionC2 << "\n";
  os << indent << "BeadingCV: " << this->BeadingCV << "\n";
  os << indent << "BeadingLength: " << this->BeadingLength << "\n";
  os << indent << "GRatio: " << this->GRatio << "\n";
  os << indent << "GRatioModel: " << this->GRatioModel << "\n";
  os << indent << "CrossingAngle: " << this->CrossingAngle << "\n";
  os << indent << "UndulationCoherence: " << this->UndulationCoherence << "\n";
  os << indent << "BeadPhasing: " << this->BeadPhasing << "\n";
  os << indent << "PopulationShares: " << this->PopulationShares[0] << " "
     << this->PopulationShares[1] << " " << this->PopulationShares[2] << "\n";
  os << indent << "Arrangement: " << this->Arrangement << "\n";
}
