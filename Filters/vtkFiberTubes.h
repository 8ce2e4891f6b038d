/**
 * @class   vtkFiberTubes
 * @brief   closed triangle mesh around every fiber, radius from the "radius" point array
 *
 * Input: fiber polydata (docs/data-contract.md §1). Output: one watertight, consistently (outward)
 * oriented tube of triangles per fiber, following the per-point radius, with point normals; cell
 * arrays `fiber_id` and `bundle_id` copied from the fiber to each of its triangles. Rings are
 * carried along the fiber by parallel transport, so tubes do not twist at sharp bends. With
 * InnerTubes on, fibers carrying the point array `inner_radius` get a second tube at that radius
 * (the axon inside the myelin), also closed and outward, and the cell array `tube_surface` tells 0
 * (outer) from 1 (inner). Other input arrays are not passed. Bad input (no `radius`, NaN/Inf,
 * radius <= 0, no line cell) is an error naming the problem; an empty input gives an empty output.
 */
#ifndef vtkFiberTubes_h
#define vtkFiberTubes_h

#include "FiberPLIFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

class FIBERPLIFILTERS_EXPORT vtkFiberTubes : public vtkPolyDataAlgorithm
{
public:
  static vtkFiberTubes* New();
  vtkTypeMacro(vtkFiberTubes, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Number of sides of each ring, 3 to 64; other values are an error. Default is 12.
   */
  vtkSetMacro(NumberOfSides, int);
  vtkGetMacro(NumberOfSides, int);
  ///@}

  ///@{
  /**
   * Close both ends of every tube (watertight tubes). Default is on.
   */
  vtkSetMacro(Capping, bool);
  vtkGetMacro(Capping, bool);
  vtkBooleanMacro(Capping, bool);
  ///@}

  ///@{
  /**
   * Also mesh a tube at the point array inner_radius of every fiber that has it (a bad value is
   * an error naming it), after all outer tubes, with the cell array tube_surface (0 outer,
   * 1 inner). Default is off (no inner tube, no tube_surface: the output of before).
   */
  vtkSetMacro(InnerTubes, bool);
  vtkGetMacro(InnerTubes, bool);
  vtkBooleanMacro(InnerTubes, bool);
  ///@}

  ///@{
  /**
   * Number of threads, 0 = all cores. Default is 0.
   */
  vtkSetMacro(NumberOfThreads, int);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

protected:
  vtkFiberTubes() = default;
  ~vtkFiberTubes() override = default;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkFiberTubes(const vtkFiberTubes&) = delete;
  void operator=(const vtkFiberTubes&) = delete;

  int NumberOfSides = 12;
  bool Capping = true;
  bool InnerTubes = false;
  int NumberOfThreads = 0;
};

#endif
