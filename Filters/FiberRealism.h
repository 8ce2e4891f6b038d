/**
 * @file FiberRealism.h
 * @brief what FiberCubeSource and FiberBundleSource do alike with the realism knobs
 *
 * The knobs themselves are computed in the Core (Tissue/ShapeOptions.h, Undulation, Beading,
 * Myelin); here only the point array `inner_radius` (docs/data-contract.md §2) is added beside
 * `radius` when myelin is on.
 */
#ifndef FiberRealism_h
#define FiberRealism_h

#include "Tissue/Myelin.h"

#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

namespace fiberpli
{

/// With myelin on (GRatio > 0), adds the point array `inner_radius` (µm): the axon's radius inside
/// the sheath, from every point's `radius` (the outer radius, the one collisions use) by the
/// g-ratio model. Does nothing with myelin off, so the output is unchanged.
inline void AddInnerRadius(vtkPolyData* output, const ShapeOptions& realism)
{
  vtkDataArray* radius = output->GetPointData()->GetArray("radius");
  if (!realism.myelinated() || !radius)
    return;
  vtkNew<vtkDoubleArray> inner;
  inner->SetName("inner_radius");
  inner->SetNumberOfTuples(radius->GetNumberOfTuples());
  for (vtkIdType i = 0; i < radius->GetNumberOfTuples(); ++i)
    inner->SetValue(i, innerRadius(radius->GetTuple1(i), realism.gRatio, realism.gRatioModel));
  output->GetPointData()->AddArray(inner);
}

} // namespace fiberpli

#endif
