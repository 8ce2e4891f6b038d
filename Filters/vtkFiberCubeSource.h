/**
 * @class   vtkFiberCubeSource
 * @brief   the paper's cube benchmark: straight fibers of 1–3 perpendicular populations in a cube
 *
 * Output: fiber polydata (docs/data-contract.md §1): one polyline per fiber, point array `radius`
 * (µm), cell arrays `fiber_id` and `bundle_id` (= population: 0 along x, 1 along y, 2 along z),
 * field data `segment_length` and `seed`. Fibers are placed uniformly at random in a cube of edge
 * EdgeLength centred at the origin; points are SegmentLength apart and each is displaced uniformly
 * within ±Displacement per axis (docs/tissue-models.md §6.1). With Periodic on, the cube is a
 * periodic cell: every fiber spans exactly one period along its axis and is closed through the
 * faces (its last point is its first point shifted by EdgeLength; points unwrapped), and the cell
 * goes to field data `periodic_cell` (xmin xmax ymin ymax zmin zmax) for the solver and the
 * writers. Identical properties give identical output. Invalid properties give an error naming the
 * property and an empty output. Pieces (docs/tissue-models.md §9): piece p of P holds the
 * contiguous range [N·p/P, N·(p+1)/P) of the N fibers (global fiber ids, field data on every
 * piece), so under MPI every rank makes only its own fibers and the pieces in rank order are the
 * serial output for any P.
 */
#ifndef vtkFiberCubeSource_h
#define vtkFiberCubeSource_h

#include "FiberPLIFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

class FIBERPLIFILTERS_EXPORT vtkFiberCubeSource : public vtkPolyDataAlgorithm
{
public:
  static vtkFiberCubeSource* New();
  vtkTypeMacro(vtkFiberCubeSource, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Number of mutually perpendicular populations: 1 (x), 2 (x, y) or 3 (x, y, z). Default is 1.
   */
  vtkSetMacro(Populations, int);
  vtkGetMacro(Populations, int);
  ///@}

  ///@{
  /**
   * Total number of fibers, split as evenly as possible over the populations. Default is 1000.
   */
  vtkSetMacro(NumberOfFibers, int);
  vtkGetMacro(NumberOfFibers, int);
  ///@}

  ///@{
  /**
   * Cube edge in µm; the cube is centred at the origin. Must exceed 2 × FiberRadius.
   * Default is 51.96 (= √3 · 30, the paper's benchmark).
   */
  vtkSetMacro(EdgeLength, double);
  vtkGetMacro(EdgeLength, double);
  ///@}

  ///@{
  /**
   * Fiber radius in µm, > 0 (median or mean with a RadiusSpread). Default is 0.8.
   */
  vtkSetMacro(FiberRadius, double);
  vtkGetMacro(FiberRadius, double);
  ///@}

  ///@{
  /**
   * Distance of consecutive fiber points in µm before displacement, > 0. Default is 2.
   */
  vtkSetMacro(SegmentLength, double);
  vtkGetMacro(SegmentLength, double);
  ///@}

  ///@{
  /**
   * Maximum random displacement of every point per axis in µm (uniform in ±D), >= 0.
   * Default is 0.5.
   */
  vtkSetMacro(Displacement, double);
  vtkGetMacro(Displacement, double);
  ///@}

  ///@{
  /**
   * Spread s of the fiber radii, >= 0 (0 = all radii FiberRadius). Default is 0.
   */
  vtkSetMacro(RadiusSpread, double);
  vtkGetMacro(RadiusSpread, double);
  ///@}

  ///@{
  /**
   * Radius distribution: 0 LogNormal, 1 Uniform, 2 Gamma, 3 Constant (as in
   * FiberBundleSource). Default is 3 (Constant: every radius FiberRadius).
   */
  vtkSetMacro(RadiusDistribution, int);
  vtkGetMacro(RadiusDistribution, int);
  ///@}

  ///@{
  /**
   * The cube is a periodic cell (fibers closed through its faces, field data periodic_cell).
   * Default is off.
   */
  vtkSetMacro(Periodic, bool);
  vtkGetMacro(Periodic, bool);
  vtkBooleanMacro(Periodic, bool);
  ///@}

  ///@{
  /**
   * Target fiber volume fraction in (0, 1): the fiber count is the smallest for which
   * Σ π r² · EdgeLength reaches at least this fraction of the cube (fibers added to the
   * populations in turn). 0 = use NumberOfFibers. Default is 0.
   */
  vtkSetMacro(VolumeFraction, double);
  vtkGetMacro(VolumeFraction, double);
  ///@}

  ///@{
  /**
   * Placement across a periodic cell: 0 = Random (uniform, default), 1 = Lattice (jittered sites of
   * an ordered lattice commensurate with the cell; needs Periodic on).
   */
  vtkSetMacro(Seeding, int);
  vtkGetMacro(Seeding, int);
  ///@}

  ///@{
  /**
   * Seed of the random placement; the same seed gives the same fibers. Default is 42.
   */
  vtkSetMacro(Seed, int);
  vtkGetMacro(Seed, int);
  ///@}

  ///@{
  /**
   * Target tortuosity (path length / end-to-end distance) of every fiber, >= 1 (at most 3): a
   * smooth random undulation whose amplitude is calibrated per fiber, Displacement included
   * (docs/tissue-models.md §10.1). 1 = off (straight fibers). Default is 1.
   */
  vtkSetMacro(Tortuosity, double);
  vtkGetMacro(Tortuosity, double);
  ///@}
  ///@{
  /**
   * Typical wavelength of the undulation in µm, > 0 (in a periodic cell rounded to whole waves per
   * period). Default is 20.
   */
  vtkSetMacro(UndulationWavelength, double);
  vtkGetMacro(UndulationWavelength, double);
  ///@}
  ///@{
  /**
   * Target ⟨cos²⟩ of the fibers' end-to-end directions about their population's axis, in (1/3, 1];
   * 1 = off (docs/tissue-models.md §10.2). Default is 1.
   */
  vtkSetMacro(DispersionC2, double);
  vtkGetMacro(DispersionC2, double);
  ///@}
  ///@{
  /**
   * Coefficient of variation of the radius along each fiber, 0 to 1 (0 = off): a smooth
   * log-normal profile whose mean over the fiber is its radius (docs/tissue-models.md §10.3).
   * Default is 0.
   */
  vtkSetMacro(BeadingCV, double);
  vtkGetMacro(BeadingCV, double);
  ///@}
  ///@{
  /**
   * Correlation length of the radius variation in µm, > 0. Default is 5.
   */
  vtkSetMacro(BeadingLength, double);
  vtkGetMacro(BeadingLength, double);
  ///@}
  ///@{
  /**
   * g-ratio (inner / outer radius) in (0, 1); 0 = no myelin. With myelin the output has the point
   * array inner_radius beside radius (= the outer radius). Default is 0.
   */
  vtkSetMacro(GRatio, double);
  vtkGetMacro(GRatio, double);
  ///@}
  ///@{
  /**
   * g-ratio model with myelin on: 0 = Constant (inner = GRatio · outer), 1 = Lee2019 (myelin
   * thickness 0.35 + 0.006·d + 0.024·ln d µm of the inner diameter d; GRatio only switches it on).
   * Default is 0.
   */
  vtkSetMacro(GRatioModel, int);
  vtkGetMacro(GRatioModel, int);
  ///@}

  ///@{
  /**
   * Degrees between the axes of populations 0 and 1, 0 to 90 (population 2 stays along z). In a
   * periodic cell the nearest small-integer lattice direction is taken and reported as field data
   * population_axes. Other than 90 needs Seeding Random. Default is 90 (x and y).
   */
  vtkSetMacro(CrossingAngle, double);
  vtkGetMacro(CrossingAngle, double);
  ///@}

  ///@{
  /**
   * µm, >= 0: with Tortuosity > 1, the undulation of each population is one random field over the
   * cube instead of independent modes per fiber, with this transverse coherence length ξ: fibers
   * whose axes are r apart undulate with correlation about exp(−r²/2ξ²), so neighbours bend
   * together (as axons of a fascicle do) and dense cells keep their undulation. Needs every
   * population along a coordinate axis (CrossingAngle 90). Default is 0 (off: every fiber
   * undulates independently).
   */
  vtkSetMacro(UndulationCoherence, double);
  vtkGetMacro(UndulationCoherence, double);
  ///@}

  ///@{
  /**
   * With Seeding Lattice, Periodic and BeadingCV > 0: each fiber's radius profile is turned along
   * it (a cyclic shift by whole points) so that its beads meet those of its neighbours least
   * (docs/tissue-models.md §10.3). Default is off (every profile as drawn).
   */
  vtkSetMacro(BeadPhasing, bool);
  vtkGetMacro(BeadPhasing, bool);
  vtkBooleanMacro(BeadPhasing, bool);
  ///@}
  ///@{
  /**
   * Relative shares of populations 0, 1, 2 (fibers with NumberOfFibers, volume with
   * VolumeFraction), each > 0; only the first Populations values are used. All equal = today's
   * even split. Default is 1, 1, 1.
   */
  vtkSetVector3Macro(PopulationShares, double);
  vtkGetVector3Macro(PopulationShares, double);
  ///@}
  ///@{
  /**
   * How the populations share the cell: 0 = Auto (each Seeding's own), 1 = Interwoven (mixed
   * everywhere), 2 = Sheets (two populations in two slabs along z). Default is 0.
   */
  vtkSetMacro(Arrangement, int);
  vtkGetMacro(Arrangement, int);
  ///@}

protected:
  vtkFiberCubeSource();
  ~vtkFiberCubeSource() override = default;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  int ExecutePiece(vtkInformationVector* outputVector);

  vtkFiberCubeSource(const vtkFiberCubeSource&) = delete;
  void operator=(const vtkFiberCubeSource&) = delete;

  int Populations = 1;
  int NumberOfFibers = 1000;
  double EdgeLength = 51.96152422706632;
  double FiberRadius = 0.8;
  double SegmentLength = 2.0;
  double Displacement = 0.5;
  double RadiusSpread = 0.0;
  int RadiusDistribution = 3;
  bool Periodic = false;
  double VolumeFraction = 0.0;
  int Seeding = 0;
  int Seed = 42;
  double Tortuosity = 1.0;
  double UndulationWavelength = 20.0;
  double DispersionC2 = 1.0;
  double BeadingCV = 0.0;
  double BeadingLength = 5.0;
  double GRatio = 0.0;
  int GRatioModel = 0;
  double CrossingAngle = 90.0;
  double UndulationCoherence = 0.0;
  bool BeadPhasing = false;
  double PopulationShares[3] = { 1.0, 1.0, 1.0 };
  int Arrangement = 0;
};

#endif
