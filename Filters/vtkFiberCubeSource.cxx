#include "vtkFiberCubeSource.h"

#include "FiberProgress.h"
#include "FiberFieldData.h"
#include "FiberPolyData.h"
#include "Tissue/CubeGenerator.h"

#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>

vtkStandardNewMacro(vtkFiberCubeSource);

//------------------------------------------------------------------------------
// Construct with 1 population of 1000 fibers in a cube of edge √3·30 µm, radius 0.8 µm,
// segment length 2 µm, displacement 0.5 µm, seed 42.
vtkFiberCubeSource::vtkFiberCubeSource()
{
  this->SetNumberOfInputPorts(0);
}

//------------------------------------------------------------------------------
int vtkFiberCubeSource::RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  const fiberpli::AbortScope abortScope(this); // an abort applies to this execution only
  vtkPolyData* output = vtkPolyData::GetData(outputVector);

  if (!fiberpli::CheckSeed(this, "FiberCubeSource", this->Seed))
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
  options.radiusSpread = this->RadiusSpread;
  options.radiusDistribution = static_cast<fiberpli::RadiusDistribution>(this->RadiusDistribution);
  options.periodic = this->Periodic;
  options.volumeFraction = this->VolumeFraction;
  options.seeding = static_cast<fiberpli::CubeSeeding>(this->Seeding);
  const std::string invalid = fiberpli::validateCubeOptions(options);
  if (!invalid.empty())
  {
    vtkErrorMacro(<< "FiberCubeSource: " << invalid);
    return 0;
  }

  this->UpdateProgress(0.0);
  const fiberpli::FiberModel model = fiberpli::generateCube(options);
  this->UpdateProgress(0.8);
  fiberpli::FiberPolyData::FromModel(model, output);

  fiberpli::FiberPolyData::AddSourceFieldData(output, this->SegmentLength, this->Seed);
  if (this->Periodic)
  {
    fiberpli::AddPeriodicCell(output, fiberpli::cubeCell(options));
  }
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
}
