#include "vtkFiberSectionAlgorithm.h"

#include "FiberAdapter.h"
#include "FiberPolyData.h"
#include "FiberTileExchange.h"
#include "Model/VolumeOfInterest.h"

#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkPolyData.h>

#include <algorithm>

//------------------------------------------------------------------------------
vtkFiberSectionAlgorithm::vtkFiberSectionAlgorithm()
  : Fibers(std::make_unique<fiberpli::FiberModelCache>())
{
}

//------------------------------------------------------------------------------
vtkFiberSectionAlgorithm::~vtkFiberSectionAlgorithm() = default;

//------------------------------------------------------------------------------
int vtkFiberSectionAlgorithm::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

//------------------------------------------------------------------------------
int vtkFiberSectionAlgorithm::RequestUpdateExtent(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  fiberpli::FiberTileExchange::RequestPiece(
    request, outputVector, inputVector[0]->GetInformationObject(0));
  return 1;
}

//------------------------------------------------------------------------------
std::string vtkFiberSectionAlgorithm::VolumeToPlan(
  vtkInformationVector* inputVector, double volume[6], bool& noFibers)
{
  std::copy(this->VolumeOfInterest, this->VolumeOfInterest + 6, volume);
  noFibers = false;
  if (!fiberpli::isBoundsSentinel(this->VolumeOfInterest) ||
    this->GetNumberOfInputConnections(0) == 0)
  {
    return {};
  }
  double bounds[6];
  const std::string error = fiberpli::FiberTileExchange::UpdateBounds(this,
    inputVector->GetInformationObject(0), fiberpli::ProxyName(this), bounds, this->Fibers.get());
  noFibers = error.empty() && !(bounds[0] <= bounds[1]); // no fiber on any rank
  if (bounds[0] <= bounds[1])
  {
    std::copy(bounds, bounds + 6, volume);
  }
  return error;
}

//------------------------------------------------------------------------------
vtkFiberSectionAlgorithm::PlanStamp vtkFiberSectionAlgorithm::StampFor(const double volume[6])
{
  PlanStamp stamp;
  stamp.time = this->GetMTime();
  std::copy(volume, volume + 6, stamp.volume);
  return stamp;
}

//------------------------------------------------------------------------------
bool vtkFiberSectionAlgorithm::PlanHolds(const PlanStamp& stamp, const double volume[6])
{
  return stamp.time == this->GetMTime() && std::equal(volume, volume + 6, stamp.volume);
}

//------------------------------------------------------------------------------
void vtkFiberSectionAlgorithm::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "VolumeOfInterest:";
  for (double v : this->VolumeOfInterest)
  {
    os << " " << v;
  }
  os << "\n" << indent << "VoxelSize: " << this->VoxelSize << "\n";
  os << indent << "PixelSize: " << this->PixelSize << "\n";
}
