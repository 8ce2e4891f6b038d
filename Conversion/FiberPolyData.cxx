#include "FiberPolyData.h"

#include "FiberFieldData.h"
#include "FiberInnerRadii.h"

#include <vtkAlgorithm.h>
#include <vtkAlgorithmOutput.h>
#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIdTypeArray.h>
#include <vtkInformation.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <vtkVariant.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>

namespace fiberpli
{

namespace
{
// The id at cell `c` as an integer in [lo, hi]; false (and `text` the value as read) when it is
// not one: NaN, a fraction or out of range in a floating-point array, a 64-bit value beyond hi.
bool readId(
  vtkDataArray* ids, vtkIdType c, long long lo, long long hi, long long& out, std::string& text)
{
  const int type = ids->GetDataType();
  if (type == VTK_FLOAT || type == VTK_DOUBLE)
  {
    const double v = ids->GetComponent(c, 0);
    std::ostringstream t;
    t << v;
    text = t.str();
    // 2^63 is exactly representable; every double below it (and >= -2^63) fits a long long.
    if (!(v == std::floor(v)) || !(v >= static_cast<double>(lo)) ||
      !(v <= static_cast<double>(hi)) || v >= 9223372036854775808.0)
    {
      return false;
    }
    out = static_cast<long long>(v);
    return true;
  }
  const vtkVariant value = ids->GetVariantValue(c * ids->GetNumberOfComponents());
  text = value.ToString();
  if (type == VTK_UNSIGNED_LONG || type == VTK_UNSIGNED_LONG_LONG)
  {
    const unsigned long long u = value.ToUnsignedLongLong();
    if (u > static_cast<unsigned long long>(hi))
    {
      return false;
    }
    out = static_cast<long long>(u);
    return true;
  }
  out = value.ToLongLong();
  return out >= lo && out <= hi;
}
} // namespace

void FiberPolyData::RequestAllFibers(vtkInformation* inputInfo)
{
  inputInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), 0);
  inputInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), 1);
  inputInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
}

int FiberPolyData::RequestedPiece(vtkInformation* outInfo)
{
  const auto key = vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER();
  return outInfo && outInfo->Has(key) ? outInfo->Get(key) : 0;
}

int FiberPolyData::RequestedPieces(vtkInformation* outInfo)
{
  const auto key = vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES();
  return outInfo && outInfo->Has(key) ? outInfo->Get(key) : 1;
}

void FiberPolyData::UpdateAllFibers(vtkAlgorithm* algorithm, vtkInformation* inputInfo)
{
  // Update the connected output port (not always port 0 of the producer).
  auto* exec = vtkStreamingDemandDrivenPipeline::SafeDownCast(algorithm->GetInputExecutive(0, 0));
  if (inputInfo && exec && algorithm->GetNumberOfInputConnections(0) > 0)
  {
    RequestAllFibers(inputInfo);
    exec->Update(algorithm->GetInputConnection(0, 0)->GetIndex());
  }
}

void FiberPolyData::AddSourceFieldData(vtkPolyData* output, double segmentLength, int seed)
{
  AddFieldDoubles(output, fiberfield::kSegmentLength, { segmentLength });
  AddFieldInt(output, fiberfield::kSeed, seed);
}

void FiberPolyData::FromSourceModel(
  const FiberModel& model, vtkPolyData* output, double segmentLength, int seed)
{
  FromModel(model, output);
  AddInnerRadii(model, output);
  AddSourceFieldData(output, segmentLength, seed);
}

bool FiberPolyData::IsEmpty(vtkPolyData* input)
{
  return input == nullptr || (input->GetNumberOfPoints() == 0 && input->GetNumberOfCells() == 0);
}

FiberConversion FiberPolyData::ToModel(vtkPolyData* input, const std::string& who)
{
  FiberConversion result;
  if (IsEmpty(input))
  {
    return result;
  }
  const vtkIdType numLines = input->GetNumberOfLines();
  const vtkIdType otherCells =
    input->GetNumberOfVerts() + input->GetNumberOfPolys() + input->GetNumberOfStrips();
  if (numLines == 0)
  {
    result.error = who + ": the input has " + std::to_string(input->GetNumberOfCells()) +
      " cells but no line cell: fibers are polylines";
    return result;
  }
  vtkDataArray* radius = input->GetPointData()->GetArray(fiberfield::kRadius);
  if (radius == nullptr)
  {
    result.error =
      who + ": the input has no point array 'radius' (fiber radius in µm at each point)";
    return result;
  }
  if (radius->GetNumberOfComponents() != 1)
  {
    result.error = who + ": the point array 'radius' has " +
      std::to_string(radius->GetNumberOfComponents()) + " components, expected 1";
    return result;
  }
  vtkPoints* points = input->GetPoints();
  const vtkIdType numPoints = input->GetNumberOfPoints();
  if (points == nullptr || radius->GetNumberOfTuples() != numPoints)
  {
    result.error = who + ": the point array 'radius' has " +
      std::to_string(radius->GetNumberOfTuples()) + " values for " + std::to_string(numPoints) +
      " points";
    return result;
  }
  vtkDataArray* fiberIds = input->GetCellData()->GetArray(fiberfield::kFiberId);
  vtkDataArray* bundleIds = input->GetCellData()->GetArray(fiberfield::kBundleId);
  for (vtkDataArray* ids : { fiberIds, bundleIds })
  {
    if (ids && ids->GetNumberOfTuples() != input->GetNumberOfCells())
    {
      result.error = who + ": the cell array '" + std::string(ids->GetName()) + "' has " +
        std::to_string(ids->GetNumberOfTuples()) + " values for " +
        std::to_string(input->GetNumberOfCells()) + " cells";
      return result;
    }
  }
  // Lines come after verts in the cell numbering of vtkPolyData.
  const vtkIdType firstLineCell = input->GetNumberOfVerts();

  std::size_t shortFibers = 0;
  result.model.fibers.reserve(static_cast<std::size_t>(numLines));
  vtkIdType lineIndex = 0;
  auto iter = vtk::TakeSmartPointer(input->GetLines()->NewIterator());
  for (iter->GoToFirstCell(); !iter->IsDoneWithTraversal(); iter->GoToNextCell(), ++lineIndex)
  {
    vtkIdType n = 0;
    const vtkIdType* ids = nullptr;
    iter->GetCurrentCell(n, ids);
    const vtkIdType cellId = firstLineCell + lineIndex;
    if (n < 2)
    {
      ++shortFibers;
      continue;
    }
    std::vector<long long> pointIds(ids, ids + n);
    Fiber f;
    f.id = cellId;
    f.bundle = 0;
    long long value = 0;
    std::string text;
    const auto badId = [&](const char* name, const char* range)
    {
      result.error = who + ": line cell " + std::to_string(cellId) + ": " + name + " is " + text +
        ", must be an integer in " + range;
      result.model.fibers.clear();
      result.sourceCell.clear();
      result.sourcePoints.clear();
    };
    if (fiberIds)
    {
      if (!readId(fiberIds, cellId, std::numeric_limits<long long>::min(),
            std::numeric_limits<long long>::max(), value, text))
      {
        badId(fiberfield::kFiberId, "[-2^63, 2^63)");
        return result;
      }
      f.id = value;
    }
    if (bundleIds)
    {
      if (!readId(bundleIds, cellId, std::numeric_limits<int>::min(),
            std::numeric_limits<int>::max(), value, text))
      {
        badId(fiberfield::kBundleId, "[-2^31, 2^31)");
        return result;
      }
      f.bundle = static_cast<int>(value);
    }
    f.points.resize(static_cast<std::size_t>(n));
    f.radii.resize(static_cast<std::size_t>(n));
    for (vtkIdType i = 0; i < n; ++i)
    {
      if (ids[i] < 0 || ids[i] >= numPoints)
      {
        result.error = who + ": line cell " + std::to_string(cellId) + " refers to point " +
          std::to_string(ids[i]) + ", but the input has " + std::to_string(numPoints) + " points";
        result.model.fibers.clear();
        result.sourceCell.clear();
        result.sourcePoints.clear();
        return result;
      }
      double p[3];
      points->GetPoint(ids[i], p);
      f.points[static_cast<std::size_t>(i)] = { p[0], p[1], p[2] };
      f.radii[static_cast<std::size_t>(i)] = radius->GetComponent(ids[i], 0);
    }
    result.model.fibers.push_back(std::move(f));
    result.sourceCell.push_back(cellId);
    result.sourcePoints.push_back(std::move(pointIds));
  }

  std::size_t modelIndex = 0;
  const std::string invalid = validateModel(result.model, &modelIndex);
  if (!invalid.empty())
  {
    // The Core message counts fibers of the model; name the input cell as well.
    std::ostringstream msg;
    msg << who << ": ";
    if (modelIndex < result.sourceCell.size())
    {
      msg << "line cell " << result.sourceCell[modelIndex] << ", ";
    }
    msg << invalid;
    result.error = msg.str();
    result.model.fibers.clear();
    result.sourceCell.clear();
    result.sourcePoints.clear();
    return result;
  }

  std::ostringstream warn;
  if (shortFibers > 0)
  {
    warn << who << ": " << shortFibers << " fiber(s) with fewer than 2 points dropped. ";
  }
  if (otherCells > 0)
  {
    warn << who << ": " << otherCells
         << " vertex/polygon/strip cell(s) are not fibers and were ignored.";
  }
  result.warning = warn.str();
  return result;
}

void FiberPolyData::PassArrays(vtkPolyData* input, const FiberConversion& conversion,
  const std::vector<std::vector<double>>& sourceIndex, vtkPolyData* output)
{
  const auto isContract = [](const char* name)
  {
    const std::string n = name ? name : "";
    return n == fiberfield::kRadius || n == fiberfield::kFiberId || n == fiberfield::kBundleId;
  };
  vtkCellData* inCells = input->GetCellData();
  for (int a = 0; a < inCells->GetNumberOfArrays(); ++a)
  {
    vtkAbstractArray* src = inCells->GetAbstractArray(a);
    if (src == nullptr || isContract(src->GetName()) ||
      src->GetNumberOfTuples() != input->GetNumberOfCells())
    {
      continue;
    }
    vtkSmartPointer<vtkAbstractArray> dst = vtk::TakeSmartPointer(src->NewInstance());
    dst->SetName(src->GetName());
    dst->SetNumberOfComponents(src->GetNumberOfComponents());
    dst->SetNumberOfTuples(static_cast<vtkIdType>(conversion.sourceCell.size()));
    for (std::size_t f = 0; f < conversion.sourceCell.size(); ++f)
    {
      dst->SetTuple(
        static_cast<vtkIdType>(f), static_cast<vtkIdType>(conversion.sourceCell[f]), src);
    }
    output->GetCellData()->AddArray(dst);
  }

  vtkPointData* inPoints = input->GetPointData();
  const vtkIdType numOut = output->GetNumberOfPoints();
  for (int a = 0; a < inPoints->GetNumberOfArrays(); ++a)
  {
    vtkAbstractArray* src = inPoints->GetAbstractArray(a);
    if (src == nullptr || isContract(src->GetName()) ||
      src->GetNumberOfTuples() != input->GetNumberOfPoints())
    {
      continue;
    }
    vtkDataArray* srcData = vtkDataArray::SafeDownCast(src);
    const bool interpolate =
      srcData && (src->GetDataType() == VTK_FLOAT || src->GetDataType() == VTK_DOUBLE);
    vtkSmartPointer<vtkAbstractArray> dst = vtk::TakeSmartPointer(src->NewInstance());
    dst->SetName(src->GetName());
    dst->SetNumberOfComponents(src->GetNumberOfComponents());
    dst->SetNumberOfTuples(numOut);
    vtkIdType out = 0;
    for (std::size_t f = 0; f < conversion.sourcePoints.size(); ++f)
    {
      const std::vector<long long>& ids = conversion.sourcePoints[f];
      const std::size_t count = sourceIndex.empty() ? ids.size() : sourceIndex[f].size();
      for (std::size_t i = 0; i < count; ++i, ++out)
      {
        const double s = sourceIndex.empty() ? static_cast<double>(i) : sourceIndex[f][i];
        auto i0 = static_cast<std::size_t>(std::max(0.0, std::floor(s)));
        i0 = std::min(i0, ids.size() - 1);
        const double t = s - static_cast<double>(i0);
        if (interpolate && t > 0.0 && i0 + 1 < ids.size())
        {
          vtkDataArray::SafeDownCast(dst)->InterpolateTuple(
            out, ids[i0], srcData, ids[i0 + 1], srcData, t);
        }
        else
        {
          dst->SetTuple(out, ids[i0], src);
        }
      }
    }
    output->GetPointData()->AddArray(dst);
  }
}

void FiberPolyData::FromModel(const FiberModel& model, vtkPolyData* output)
{
  const auto numPoints = static_cast<vtkIdType>(model.numberOfPoints());
  const auto numFibers = static_cast<vtkIdType>(model.fibers.size());

  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(numPoints);
  vtkNew<vtkDoubleArray> radius;
  radius->SetName(fiberfield::kRadius);
  radius->SetNumberOfTuples(numPoints);
  vtkNew<vtkIdTypeArray> offsets;
  offsets->SetNumberOfTuples(numFibers + 1);
  vtkNew<vtkIdTypeArray> connectivity;
  connectivity->SetNumberOfTuples(numPoints);
  vtkNew<vtkIdTypeArray> fiberId;
  fiberId->SetName(fiberfield::kFiberId);
  fiberId->SetNumberOfTuples(numFibers);
  vtkNew<vtkIntArray> bundleId;
  bundleId->SetName(fiberfield::kBundleId);
  bundleId->SetNumberOfTuples(numFibers);

  vtkIdType next = 0;
  for (vtkIdType c = 0; c < numFibers; ++c)
  {
    const Fiber& f = model.fibers[static_cast<std::size_t>(c)];
    offsets->SetValue(c, next);
    for (std::size_t i = 0; i < f.points.size(); ++i, ++next)
    {
      points->SetPoint(next, f.points[i].x, f.points[i].y, f.points[i].z);
      radius->SetValue(next, f.radii[i]);
      connectivity->SetValue(next, next);
    }
    fiberId->SetValue(c, static_cast<vtkIdType>(f.id));
    bundleId->SetValue(c, f.bundle);
  }
  offsets->SetValue(numFibers, next);

  vtkNew<vtkCellArray> lines;
  lines->SetData(offsets, connectivity);

  output->Initialize();
  output->SetPoints(points);
  output->SetLines(lines);
  output->GetPointData()->AddArray(radius);
  output->GetPointData()->SetActiveScalars(fiberfield::kRadius);
  output->GetCellData()->AddArray(fiberId);
  output->GetCellData()->AddArray(bundleId);
}

//------------------------------------------------------------------------------
const FiberConversion& FiberModelCache::Get(vtkPolyData* input, const std::string& who)
{
  // The pointer too: after the input connection is switched another object may have the same MTime.
  if (!this->Valid || this->Input != input || this->Time != input->GetMTime())
  {
    this->Value = FiberPolyData::ToModel(input, who);
    if (this->Value.ok())
    {
      // The PLI tissue is myelinated where fibers carry inner_radius (docs/pli-simulation.md §3.2).
      this->Value.error = ReadInnerRadii(input, this->Value, who);
    }
    this->Value.sourceCell = {};
    this->Value.sourcePoints = {};
    this->Input = input;
    this->Time = input->GetMTime();
    this->Valid = true;
  }
  return this->Value;
}

} // namespace fiberpli
