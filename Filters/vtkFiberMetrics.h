/**
 * @class   vtkFiberMetrics
 * @brief   measures a fiber model: volume fraction, collisions and smallest gap, orientation order,
 *          tortuosity, link length and radius ranges
 *
 * Input: fiber polydata (docs/data-contract.md §1). The measurements are the Core's (Core/Metrics),
 * independent of the solver's own collision code.
 *
 * Output port 0: the input fibers passed through, with cell arrays `fiber_length` and
 * `tortuosity` (arc length / end-to-end distance) and field data holding every value of the
 * summary table. Output port 1 ("Summary"): a one-row vtkTable. Output port 2 ("Bundles"): one row
 * per bundle_id. Output port 3 ("Populations"): the realism of each population (bundle_id) —
 * tortuosity range, c2 of end-to-end directions and of segments about the population's axis,
 * radius CV along fibers, g-ratio, mixing share. Output ports 4–7: histogram tables of point radii,
 * fiber tortuosity, point g-ratios and link angles to their population's axis (columns
 * bin_extents = bin centres and count; field data histogram_range and bin_width; Bar Chart View).
 * Column and field-data names are listed in docs/metrics.md.
 *
 * Volume fraction: the covered fraction of `Box` (xmin xmax ymin ymax zmin zmax; any min > max,
 * the default, means the bounds of the fiber points), or — when the input carries the
 * `periodic_cell` field data and UsePeriodicCell is on — of the whole periodic cell, counting every
 * periodic image. It is a voxel-centre count on a grid of `VoxelSize` with a rigorous error bound
 * (volume_fraction_error), or a Monte Carlo estimate with its standard error. Colliding pairs and
 * the smallest surface gap compare every capsule pair except chain neighbours of one fiber (the
 * solver's contract), by minimum image in a periodic cell.
 *
 * Under MPI only piece 0 measures (all the fibers it receives); the other pieces give empty
 * outputs, so tables are not appended once per rank. Bad input or options are errors naming the
 * value; an empty input gives empty outputs.
 */
#ifndef vtkFiberMetrics_h
#define vtkFiberMetrics_h

#include "FiberPLIFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

class FIBERPLIFILTERS_EXPORT vtkFiberMetrics : public vtkPolyDataAlgorithm
{
public:
  static vtkFiberMetrics* New();
  vtkTypeMacro(vtkFiberMetrics, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Box of the volume fraction (µm): xmin xmax ymin ymax zmin zmax. Any min > max (the default
   * 1 -1 1 -1 1 -1) means the bounds of the fiber points. Ignored when the periodic cell is used.
   */
  vtkSetVector6Macro(Box, double);
  vtkGetVector6Macro(Box, double);
  ///@}

  ///@{
  /**
   * Use the input's `periodic_cell` field data when present: volume fraction of the whole cell,
   * pairs by minimum image. Default is on.
   */
  vtkSetMacro(UsePeriodicCell, bool);
  vtkGetMacro(UsePeriodicCell, bool);
  vtkBooleanMacro(UsePeriodicCell, bool);
  ///@}

  ///@{
  /**
   * Voxel edge of the volume fraction (µm), 0 = automatic (an eighth of the smallest radius,
   * coarsened to at most 2e8 voxels). Default is 0.
   */
  vtkSetMacro(VoxelSize, double); // checked by the Core
  vtkGetMacro(VoxelSize, double);
  ///@}

  enum VolumeFractionMethods
  {
    VOXELS = 0,
    MONTE_CARLO = 1
  };

  ///@{
  /**
   * How the volume fraction is measured: 0 Voxels (deterministic count, volume_fraction_error is
   * a rigorous bound), 1 MonteCarlo (Samples random points from Seed, volume_fraction_error is the
   * standard error, 0.05 % at the default 10⁶ samples). Default is 1: the voxel bound at automatic
   * voxels is often ±10–25 points, far wider than the count's real error.
   */
  vtkSetMacro(VolumeFractionMethod, int); // checked at execution
  vtkGetMacro(VolumeFractionMethod, int);
  vtkSetMacro(Samples, int); // checked by the Core
  vtkGetMacro(Samples, int);
  vtkSetMacro(Seed, int);
  vtkGetMacro(Seed, int);
  ///@}

  ///@{
  /**
   * Compute the volume fraction / the colliding pairs and smallest gap. Both default on.
   */
  vtkSetMacro(ComputeVolumeFraction, bool);
  vtkGetMacro(ComputeVolumeFraction, bool);
  vtkBooleanMacro(ComputeVolumeFraction, bool);
  vtkSetMacro(ComputeCollisions, bool);
  vtkGetMacro(ComputeCollisions, bool);
  vtkBooleanMacro(ComputeCollisions, bool);
  ///@}

  ///@{
  /**
   * Compute the mixing figure of the populations (Monte Carlo with Samples points from Seed in the
   * volume fraction's region; 1 unsampled for one population). Default is on.
   */
  vtkSetMacro(ComputeMixing, bool);
  vtkGetMacro(ComputeMixing, bool);
  vtkBooleanMacro(ComputeMixing, bool);
  ///@}

  ///@{
  /**
   * Bins of the histogram outputs (4–7), 1 to 1000000. Default is 20.
   */
  vtkSetMacro(HistogramBins, int); // checked by the Core
  vtkGetMacro(HistogramBins, int);
  ///@}

  ///@{
  /**
   * Number of threads, 0 = all cores. Default is 0. Results do not depend on it.
   */
  vtkSetMacro(NumberOfThreads, int);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

protected:
  vtkFiberMetrics();
  ~vtkFiberMetrics() override = default;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkFiberMetrics(const vtkFiberMetrics&) = delete;
  void operator=(const vtkFiberMetrics&) = delete;

  double Box[6] = { 1, -1, 1, -1, 1, -1 };
  bool UsePeriodicCell = true;
  double VoxelSize = 0.0;
  int VolumeFractionMethod = MONTE_CARLO;
  int Samples = 1000000;
  int Seed = 0;
  bool ComputeVolumeFraction = true;
  bool ComputeCollisions = true;
  bool ComputeMixing = true;
  int HistogramBins = 20;
  int NumberOfThreads = 0;
};

#endif
