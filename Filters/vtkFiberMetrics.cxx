#include "vtkFiberMetrics.h"

#include "FiberAdapter.h"
#include "FiberFieldData.h"
#include "FiberGuard.h"
#include "FiberInnerRadii.h"
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
#include <utility>

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

/// The two columns every per-bundle and per-population table starts with: `bundle_id` and
/// `fibers`, `rows` tuples each (owned by the table).
std::pair<vtkIntArray*, vtkIdTypeArray*> AddBundleColumns(vtkTable* table, vtkIdType rows)
{
  vtkNew<vtkIntArray> bundleId;
  bundleId->SetName("bundle_id");
  bundleId->SetNumberOfTuples(rows);
  vtkNew<vtkIdTypeArray> fibers;
  fibers->SetName("fibers");
  fibers->SetNumberOfTuples(rows);
  table->AddColumn(bundleId);
  table->AddColumn(fibers);
  return { bundleId.GetPointer(), fibers.GetPointer() };
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

/// A bar-chart table of a histogram: bin_extents (the bin centres, under the name ParaView's own
/// Histogram filter gives them, so that the Bar Chart View takes them as x and hides them as a
/// series) and count; the field data `histogram_range` (lower edge of the first bin, upper edge of
/// the last) and `bin_width`. No other column, so that the chart shows the counts alone.
void FillHistogram(vtkTable* table, const fiberpli::Histogram& h)
{
  const auto bins = static_cast<vtkIdType>(h.count.size());
  vtkDoubleArray* centre = AddColumn(table, "bin_extents", 1, bins);
  vtkNew<vtkIdTypeArray> count;
  count->SetName("count");
  count->SetNumberOfTuples(bins);
  table->AddColumn(count);
  for (vtkIdType k = 0; k < bins; ++k)
  {
    const auto i = static_cast<std::size_t>(k);
    centre->SetValue(k, h.centre(i));
    count->SetValue(k, static_cast<vtkIdType>(h.count[i]));
  }
  vtkNew<vtkDoubleArray> range, width;
  range->SetName("histogram_range");
  range->InsertNextValue(h.lo);
  range->InsertNextValue(h.hi);
  width->SetName("bin_width");
  width->InsertNextValue(h.width());
  table->GetFieldData()->AddArray(range);
  table->GetFieldData()->AddArray(width);
}

/// Output port 3: one row per population.
void FillPopulations(vtkTable* table, const fiberpli::MetricsResult& m)
{
  const auto& populations = m.realism.populations;
  const auto rows = static_cast<vtkIdType>(populations.size());
  const auto [bundleId, fibers] = AddBundleColumns(table, rows);
  vtkDoubleArray* tMin = AddColumn(table, "tortuosity_min", 1, rows);
  vtkDoubleArray* tMean = AddColumn(table, "tortuosity_mean", 1, rows);
  vtkDoubleArray* tMax = AddColumn(table, "tortuosity_max", 1, rows);
  vtkDoubleArray* axis = AddColumn(table, "axis", 3, rows);
  vtkDoubleArray* c2Ends = AddColumn(table, "c2_end_to_end", 1, rows);
  vtkDoubleArray* c2Segments = AddColumn(table, "c2_segments", 1, rows);
  vtkDoubleArray* cv = AddColumn(table, "radius_cv", 1, rows);
  vtkDoubleArray* g = AddColumn(table, "g_ratio_mean", 1, rows);
  vtkDoubleArray* mixing = AddColumn(table, "mixing_min_share", 1, rows);
  vtkDoubleArray* share = AddColumn(table, "volume_share", 1, rows);
  for (vtkIdType r = 0; r < rows; ++r)
  {
    const fiberpli::PopulationRealism& p = populations[static_cast<std::size_t>(r)];
    bundleId->SetValue(r, p.bundle);
    fibers->SetValue(r, static_cast<vtkIdType>(p.fibers));
    tMin->SetValue(r, p.tortuosity.min);
    tMean->SetValue(r, p.tortuosity.mean);
    tMax->SetValue(r, p.tortuosity.max);
    const double a[3] = { p.axis.x, p.axis.y, p.axis.z };
    axis->SetTypedTuple(r, a);
    c2Ends->SetValue(r, p.c2EndToEnd);
    c2Segments->SetValue(r, p.c2Segments);
    cv->SetValue(r, p.radiusCV);
    g->SetValue(r, p.gRatio);
    // The mixing result lists the same populations in the same (increasing) order when computed.
    const bool mixed = static_cast<std::size_t>(r) < m.mixing.minShare.size();
    mixing->SetValue(r, mixed ? m.mixing.minShare[static_cast<std::size_t>(r)] : vtkMath::Nan());
    share->SetValue(r, mixed ? m.mixing.volumeShare[static_cast<std::size_t>(r)] : vtkMath::Nan());
  }
}

} // namespace

//------------------------------------------------------------------------------
vtkFiberMetrics::vtkFiberMetrics()
{
  this->SetNumberOfOutputPorts(8);
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
int vtkFiberMetrics::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  fiberpli::FiberPolyData::RequestAllFibers(inputVector[0]->GetInformationObject(0));
  return 1;
}

//------------------------------------------------------------------------------
int vtkFiberMetrics::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // Any exception escaping the work becomes a VTK error (FiberGuard.h), never an abort.
  return fiberpli::GuardRequest(this, outputVector, fiberpli::ProxyName(this),
    [&]() -> int
    {
      const fiberpli::AbortScope abortScope(this); // an abort applies to this execution only
      if (!fiberpli::CheckThreads(this, this->NumberOfThreads))
      {
        return 0;
      }
      bool monteCarlo = false;
      if (!fiberpli::CheckEnum(this, this->VolumeFractionMethod, MONTE_CARLO,
            "VolumeFractionMethod", "0 (Voxels) or 1 (MonteCarlo)", monteCarlo))
      {
        return 0;
      }
      if (!fiberpli::CheckSeed(this, this->Seed))
      {
        return 0;
      }
      vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
      vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
      vtkTable* summary = vtkTable::GetData(outputVector, 1);
      vtkTable* bundles = vtkTable::GetData(outputVector, 2);
      vtkTable* populations = vtkTable::GetData(outputVector, 3);
      vtkTable* histograms[4] = { vtkTable::GetData(outputVector, 4),
        vtkTable::GetData(outputVector, 5), vtkTable::GetData(outputVector, 6),
        vtkTable::GetData(outputVector, 7) };
      output->Initialize();
      summary->Initialize();
      bundles->Initialize();
      populations->Initialize();
      for (vtkTable* h : histograms)
      {
        h->Initialize();
      }
      vtkInformation* outInfo = outputVector->GetInformationObject(0);
      const bool firstPiece = fiberpli::FiberPolyData::RequestedPiece(outInfo) == 0;
      if (fiberpli::FiberPolyData::IsEmpty(input) || !firstPiece)
      {
        return 1;
      }

      fiberpli::FiberConversion in =
        fiberpli::FiberPolyData::ToModel(input, fiberpli::ProxyName(this));
      if (!in.ok())
      {
        vtkErrorMacro(<< in.error);
        return 0;
      }
      if (!in.warning.empty())
      {
        vtkWarningMacro(<< in.warning);
      }
      const std::string innerError = fiberpli::ReadInnerRadii(input, in, fiberpli::ProxyName(this));
      if (!innerError.empty())
      {
        vtkErrorMacro(<< innerError);
        return 0;
      }
      fiberpli::MetricsOptions options;
      options.boxLo = { this->Box[0], this->Box[2], this->Box[4] };
      options.boxHi = { this->Box[1], this->Box[3], this->Box[5] };
      options.voxelSize = this->VoxelSize;
      options.monteCarlo = monteCarlo;
      options.samples = this->Samples;
      options.seed = static_cast<std::uint64_t>(static_cast<std::uint32_t>(this->Seed));
      options.volumeFraction = this->ComputeVolumeFraction;
      options.pairs = this->ComputeCollisions;
      options.mixing = this->ComputeMixing;
      options.histogramBins = this->HistogramBins;
      options.numberOfThreads = this->NumberOfThreads;
      if (this->UsePeriodicCell)
      {
        std::string error;
        if (!fiberpli::ReadPeriodicCell(input, options.cell, error) && !error.empty())
        {
          fiberpliErrorMacro(<< error);
          return 0;
        }
      }

      this->SetProgressText("Measuring fibers");
      fiberpli::MetricsResult m;
      if (!fiberpli::TryInMemory(
            [&] {
              m = fiberpli::computeFiberMetrics(in.model, options, fiberpli::MakeProgress(this));
            }))
      {
        fiberpliErrorMacro(
          << "out of memory measuring " << in.model.fibers.size()
          << " fibers (set FIBERPLI_MEMORY_LIMIT or lower Samples / raise VoxelSize)");
        return 0;
      }
      if (!m.error.empty())
      {
        fiberpliErrorMacro(<< m.error);
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
      // Realism per fiber: the along-fiber radius CV, and the g-ratio of myelinated fibers.
      vtkNew<vtkDoubleArray> radiusCV, gRatio;
      radiusCV->SetName("radius_cv");
      gRatio->SetName("g_ratio");
      for (vtkDoubleArray* a : { radiusCV.Get(), gRatio.Get() })
      {
        a->SetNumberOfTuples(input->GetNumberOfCells());
        a->Fill(vtkMath::Nan());
      }
      for (std::size_t f = 0; f < in.sourceCell.size(); ++f)
      {
        radiusCV->SetValue(in.sourceCell[f], m.realism.fiberRadiusCV[f]);
        gRatio->SetValue(in.sourceCell[f], m.realism.fiberGRatio[f]);
      }
      output->GetCellData()->AddArray(radiusCV);
      if (fiberpli::hasInnerRadii(in.model))
      {
        output->GetCellData()->AddArray(gRatio);
      }

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
      AddValue(summary, "box",
        { m.regionLo.x, m.regionHi.x, m.regionLo.y, m.regionHi.y, m.regionLo.z, m.regionHi.z });
      AddCount(summary, "periodic", options.cell.enabled() ? 1 : 0);
      AddCount(summary, "collisions", m.pairs.collisions);
      AddValue(summary, "min_gap", { m.pairs.minGap });
      AddValue(summary, "c2", { s.orientation.c2 });
      AddValue(summary, "mean_direction",
        { s.orientation.direction.x, s.orientation.direction.y, s.orientation.direction.z });
      AddValue(summary, "tortuosity_min", { s.tortuosityRange.min });
      AddValue(summary, "tortuosity_mean", { s.tortuosityRange.mean });
      AddValue(summary, "tortuosity_max", { s.tortuosityRange.max });
      AddValue(summary, "link_length_min", { s.linkLength.min });
      AddValue(summary, "link_length_mean", { s.linkLength.mean });
      AddValue(summary, "link_length_max", { s.linkLength.max });
      AddValue(summary, "radius_min", { s.radius.min });
      AddValue(summary, "radius_mean", { s.radius.mean });
      AddValue(summary, "radius_max", { s.radius.max });
      AddValue(summary, "radius_cv", { m.realism.radiusCV });
      AddValue(summary, "g_ratio_mean", { m.realism.gRatio });
      AddValue(summary, "mixing_min_share", { m.mixing.minimum });
      AddValue(summary, "axon_fraction", { m.axonVolume.fraction });
      AddValue(summary, "axon_fraction_error", { m.axonVolume.errorBound });
      AddValue(summary, "myelin_fraction", { m.myelinFraction });
      AddValue(summary, "extra_axonal_fraction", { m.extraAxonalFraction });
      for (vtkIdType c = 0; c < summary->GetNumberOfColumns(); ++c)
      {
        output->GetFieldData()->AddArray(summary->GetColumn(c)); // replaces same-named input arrays
      }

      const auto rows = static_cast<vtkIdType>(s.bundles.size());
      const auto [bundleId, fibers] = AddBundleColumns(bundles, rows);
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
        const double d[3] = { shape.orientation.direction.x, shape.orientation.direction.y,
          shape.orientation.direction.z };
        direction->SetTypedTuple(b, d);
        tortuosityMean->SetValue(b, shape.tortuosity.mean);
        lengthMean->SetValue(b, shape.fiberLength.mean);
      }

      FillPopulations(populations, m);
      FillHistogram(histograms[0], m.realism.radiusHistogram);
      FillHistogram(histograms[1], m.realism.tortuosityHistogram);
      FillHistogram(histograms[2], m.realism.gRatioHistogram);
      FillHistogram(histograms[3], m.realism.segmentAngleHistogram);
      return 1;
    });
}

//------------------------------------------------------------------------------
void vtkFiberMetrics::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Box: " << this->Box[0] << " " << this->Box[1] << " " << this->Box[2] << " "
     << this->Box[3] << " " << this->Box[4] << " " << this->Box[5] << "\n";
  os << indent << "UsePeriodicCell: " << this->UsePeriodicCell << "\n";
  os << indent << "VoxelSize: " << this->VoxelSize << "\n";
  os << indent << "VolumeFractionMethod: "
     << (this->VolumeFractionMethod == MONTE_CARLO ? "MonteCarlo" : "Voxels") << "\n";
  os << indent << "Samples: " << this->Samples << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "ComputeVolumeFraction: " << this->ComputeVolumeFraction << "\n";
  os << indent << "ComputeCollisions: " << this->ComputeCollisions << "\n";
  os << indent << "ComputeMixing: " << this->ComputeMixing << "\n";
  os << indent << "HistogramBins: " << this->HistogramBins << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
}
