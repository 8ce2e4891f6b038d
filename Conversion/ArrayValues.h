/**
 * @file ArrayValues.h
 * @brief a VTK data array's values as the contiguous doubles the Core takes
 *
 * AsDoubles returns the array's own memory when it is a vtkDoubleArray and copies any other numeric
 * array into `buffer`; components stay interleaved (tuple-major), as in VTK.
 */
#ifndef ArrayValues_h
#define ArrayValues_h

#include <vtkDataArray.h>
#include <vtkDoubleArray.h>

#include <cstddef>
#include <vector>

namespace fiberpli
{

/// All values of `a` as contiguous doubles (no copy when it already is a double array); valid
/// while `a` and `buffer` live.
inline const double* AsDoubles(vtkDataArray* a, std::vector<double>& buffer)
{
  if (auto* d = vtkDoubleArray::SafeDownCast(a))
  {
    return d->GetPointer(0);
  }
  const vtkIdType n = a->GetNumberOfValues();
  const int components = a->GetNumberOfComponents();
  buffer.resize(static_cast<std::size_t>(n));
  for (vtkIdType k = 0; k < n; ++k)
  {
    buffer[static_cast<std::size_t>(k)] =
      a->GetComponent(k / components, static_cast<int>(k % components));
  }
  return buffer.data();
}

} // namespace fiberpli

#endif
// VTK-HeaderTest-Exclude: ArrayValues.h
