#include "vtkFiberMetrics.h"

#include "FiberFieldData.h"
#include "FiberGuard.h"
#include "FiberPolyData.h"
#include "FiberProgress.h"
#include "Metrics/FiberMetrics.h"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIdTypeArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkMath.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkTable.h>

#include <cstdint>
#include <initializer_list>
#include <new>
#include <string>

vtkStandardNewMacro(vtkFiberMetrics);

namespace
{

/// A table column of `values.size()` components with `rows` tuples (rows > 1: set later).
vtkDoubleArray* AddColumn(vtkTable* table, const char* name, int components, vtkIdType rows)
{
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->SetNumberOfComponents(components);
  a->SetNumberOfTuples(rows);
  table->AddColumn(a);
  return a;
}

void AddValue(vtkTable* table, const char* name, std::initializer_list<double> values)
{
  vtkDoubleArray* a = AddColumn(table, name, static_cast<int>(values.size()), 1);
  int c = 0;
  for (double v : values)
  {
    a->SetComponent(0, c++, v);
  }
}

void AddCount(vtkTable* table, const char* name, long long value)
{
  vtkNew<vtkIdTypeArray> a;
  a->SetName(name);
  a->InsertNextValue(static_cast<vtkIdType>(value));
  table->AddColumn(a);
}

} // namespace

//------------------------------------------------------------------------------
vtkFiberMetrics::vtkFiberMetrics()
{
  this->SetNumberOfOutputPorts(3);
}

//------------------------------------------------------------------------------
int vtkFiberMetrics::FillOutputPortInformation(int port, vtkInformation* info)
{
  if (port == 0)
  {
    return this->Superclass::FillOutputPortInformation(port, info);
  }
  info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkTable");
  return 1;
}

//------------------------------------------------------------------------------
int vtkFiberMetrics::RequestUpdateExtent(vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  fiberpli::FiberPolyData::RequestAllFibers(inputVector[0]->GetInformationObject(0));
  return 1;
}

//------------------------------------------------------------------------------
int vtkFiberMetrics::RequestData(vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // Any exception escaping the work becomes a VTK error (FiberGuard.h), never an abort.
  return fiberpli::GuardRequest(this, outputVector, "FiberMetrics", [&]() -> int {
    const fiberpli::AbortScope abortScope(this); // an abort applies to this execution only
    if (!fiberpli::CheckThreads(this, "FiberMetrics", this->NumberOfThreads))
    {
      return 0;
    }
    if (this->VolumeFractionMethod != VOXELS && this->VolumeFractionMethod != MONTE_CARLO)
    {
      vtkErrorMacro(<< "FiberMetrics: VolumeFractionMethod is " << this->VolumeFractionMethod
                    << ", must be 0 (Voxels) or 1 (MonteCarlo)");
      return 0;
    }
    if (!fiberpli::CheckSeed(this, "FiberMetrics", this->Seed))
    {
      return 0;
    }
    vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
    vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
    vtkTable* summary = vtkTable::GetData(outputVector, 1);
    vtkTable* bundles = vtkTable::GetData(outputVector, 2);
    output->Initialize();
    summary->Initialize();
    bundles->Initialize();
    vtkInformation* outInfo = outputVector->GetInformationObject(0);
    const bool firstPiece = fiberpli::FiberPolyData::RequestedPiece(outInfo) == 0;
    if (fiberpli::FiberPolyData::IsEmpty(input) || !firstPiece)
    {
      return 1;
    }

    fiberpli::FiberConversion in = fiberpli::FiberPolyData::ToModel(input, "FiberMetrics");
    if (!in.ok())
    {
      vtkErrorMacro(<< in.error);
      return 0;
    }
    if (!in.warning.empty())
    {
      vtkWarningMacro(<< in.warning);
    }
    fiberpli::MetricsOptions options;
    options.boxLo = { this->Box[0], this->Box[2], this->Box[4] };
    options.boxHi = { this->Box[1], this->Box[3], this->Box[5] };
    options.voxelSize = this->VoxelSize;
    options.monteCarlo = this->VolumeFractionMethod == MONTE_CARLO;
    options.samples = this->Samples;
    options.seed = static_cast<std::uint64_t>(static_cast<std::uint32_t>(this->Seed));
    options.volumeFraction = this->ComputeVolumeFraction;
    options.pairs = this->ComputeCollisions;
    options.numberOfThreads = this->NumberOfThreads;
    if (this->UsePeriodicCell)
    {
      std::string error;
      if (!fiberpli::ReadPeriodicCell(input, options.cell, error) && !error.empty())
      {
        vtkErrorMacro(<< "FiberMetrics: " << error);
        return 0;
      }
    }

    this->SetProgressText("Measuring fibers");
    fiberpli::MetricsResult m;
    try
    {
      m = fiberpli::computeFiberMetrics(in.model, options, fiberpli::MakeProgress(this));
    }
    catch (const std::bad_alloc&) // no Core exception may leave through VTK (it would end pvpython)
    {
      vtkErrorMacro(<< "FiberMetrics: out of memory measuring " << in.model.fibers.size()
                    << " fibers (set FIBERPLI_MEMORY_LIMIT or lower Samples / raise VoxelSize)");
      return 0;
    }
    if (!m.error.empty())
    {
      vtkErrorMacro(<< "FiberMetrics: " << m.error);
      return 0;
    }
    if (m.aborted)
    {
      return 1;
    }

    output->ShallowCopy(input);
    vtkNew<vtkDoubleArray> length, tortuosity;
    length->SetName("fiber_length");
    tortuosity->SetName("tortuosity");
    for (vtkDoubleArray* a : { length.Get(), tortuosity.Get() })
    {
      a->SetNumberOfTuples(input->GetNumberOfCells());
      a->Fill(vtkMath::Nan()); // cells that are no fiber (dropped or not a line)
    }
    for (std::size_t f = 0; f < in.sourceCell.size(); ++f)
    {
      length->SetValue(in.sourceCell[f], m.shape.fiberLength[f]);
      tortuosity->SetValue(in.sourceCell[f], m.shape.tortuosity[f]);
    }
    output->GetCellData()->AddArray(length);
    output->GetCellData()->AddArray(tortuosity);

    const fiberpli::ShapeResult& s = m.shape;
    AddCount(summary, "fibers", static_cast<long long>(m.fibers));
    AddCount(summary, "points", static_cast<long long>(m.points));
    AddCount(summary, "links", static_cast<long long>(m.links));
    AddCount(summary, "bundles", static_cast<long long>(s.bundles.size()));
    AddValue(summary, "volume_fraction", { m.volume.fraction });
    AddValue(summary, "volume_fraction_error", { m.volume.errorBound });
    vtkNew<vtkStringArray> method;
    method->SetName("volume_fraction_method");
    method->InsertNextValue(options.monteCarlo ? "MonteCarlo" : "Voxels");
    summary->AddColumn(method);
    AddValue(summary, "voxel_size", { m.volume.voxel.x, m.volume.voxel.y, m.volume.voxel.z });
    AddValue(summary, "box", { m.regionLo.x, m.regionHi.x, m.regionLo.y, m.regionHi.y, m.regionLo.z, m.regionHi.z });
    AddCount(summary, "periodic", options.cell.enabled() ? 1 : 0);
    AddCount(summary, "collisions", m.pairs.collisions);
    AddValue(summary, "min_gap", { m.pairs.minGap });
    AddValue(summary, "c2", { s.orientation.c2 });
    AddValue(summary, "mean_direction", { s.orientation.direction.x, s.orientation.direction.y, s.orientation.direction.z });
    AddValue(summary, "tortuosity_min", { s.tortuosityRange.min });
    AddValue(summary, "tortuosity_mean", { s.tortuosityRange.mean });
    AddValue(summary, "tortuosity_max", { s.tortuosityRange.max });
    AddValue(summary, "link_length_min", { s.linkLength.min });
    AddValue(summary, "link_length_mean", { s.linkLength.mean });
    AddValue(summary, "link_length_max", { s.linkLength.max });
    AddValue(summary, "radius_min", { s.radius.min });
    AddValue(summary, "radius_mean", { s.radius.mean });
    AddValue(summary, "radius_max", { s.radius.max });
    for (vtkIdType c = 0; c < summary->GetNumberOfColumns(); ++c)
    {
      output->GetFieldData()->AddArray(summary->GetColumn(c)); // replaces same-named input arrays
    }

    const auto rows = static_cast<vtkIdType>(s.bundles.size());
    vtkNew<vtkIntArray> bundleId;
    bundleId->SetName("bundle_id");
    bundleId->SetNumberOfTuples(rows);
    vtkNew<vtkIdTypeArray> fibers;
    fibers->SetName("fibers");
    fibers->SetNumberOfTuples(rows);
    bundles->AddColumn(bundleId);
    bundles->AddColumn(fibers);
    vtkDoubleArray* c2 = AddColumn(bundles, "c2", 1, rows);
    vtkDoubleArray* direction = AddColumn(bundles, "mean_direction", 3, rows);
    vtkDoubleArray* tortuosityMean = AddColumn(bundles, "tortuosity_mean", 1, rows);
    vtkDoubleArray* lengthMean = AddColumn(bundles, "fiber_length_mean", 1, rows);
    for (vtkIdType b = 0; b < rows; ++b)
    {
      const fiberpli::BundleShape& shape = s.bundles[static_cast<std::size_t>(b)];
      bundleId->SetValue(b, shape.bundle);
      fibers->SetValue(b, static_cast<vtkIdType>(shape.fibers));
      c2->SetValue(b, shape.orientation.c2);
      const double d[3] = { shape.orientation.direction.x, shape.orientation.direction.y, shape.orientation.direction.z };
      direction->SetTypedTuple(b, d);
      tortuosityMean->SetValue(b, shape.tortuosity.mean);
      lengthMean->SetValue(b, shape.fiberLength.mean);
    }
    return 1;
  });
}

//------------------------------------------------------------------------------
void vtkFiberMetrics::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Box: " << this->Box[0] << " " << this->Box[1] << " " << this->Box[2] << " " << this->Box[3]
     << " " << this->Box[4] << " " << this->Box[5] << "\n";
  os << indent << "UsePeriodicCell: " << this->UsePeriodicCell << "\n";
  os << indent << "VoxelSize: " << this->VoxelSize << "\n";
  os << indent << "VolumeFractionMethod: " << (this->VolumeFractionMethod == MONTE_CARLO ? "MonteCarlo" : "Voxels") << "\n";
  os << indent << "Samples: " << this->Samples << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "ComputeVolumeFraction: " << this->ComputeVolumeFraction << "\n";
  os << indent << "ComputeCollisions: " << this->ComputeCollisions << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
}
