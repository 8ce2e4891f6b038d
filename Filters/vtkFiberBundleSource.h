/**
 * @class   vtkFiberBundleSource
 * @brief   bundles of fibers along a trajectory: cylinder, input polyline, crossing, Y-shape,
 * chiasm
 *
 * Output: fiber polydata (docs/data-contract.md §1): one polyline per fiber, point array `radius`
 * (µm), cell arrays `fiber_id` (0..N-1) and `bundle_id`, field data `segment_length` and `seed`.
 * The cross-section of a bundle of radius BundleRadius is filled with fibers on a triangular grid
 * of spacing FiberSpacing (or NumberOfFibers random seeds) and carried along the trajectory by a
 * rotation-minimising frame; every point is then displaced uniformly within ±Displacement per axis
 * (docs/tissue-models.md §2, §5, §6). Shapes and bundle ids:
 * - Cylinder: along x from (-Length/2, 0, 0) to (+Length/2, 0, 0); bundle 0.
 * - Trajectory: along the first line cell of the optional input port 0 (`Trajectory`); an optional
 *   point array `scale` (> 0) widens or narrows the bundle per point; bundle 0.
 * - Crossing: two bundles of length Length through the origin, at CrossingAngle in the x-y plane;
 *   bundles 0, 1.
 * - YShape: trunk along +y to the fork at the origin, halves turning to ±CrossingAngle/2; bundles
 *   0 (left), 1 (right).
 * - Chiasm: two nerves crossing at CrossingAngle; UncrossedFraction of each nerve's lateral fibers
 *   turn back to their own side on a circular arc; bundles 0, 1 crossing, 2, 3 uncrossed; nodes of
 *   Ranvier on by default.
 * Units µm and degrees. Invalid properties or a bad trajectory (fewer than 2 points, repeated
 * consecutive points, NaN) give an error naming the property or the point and an empty output;
 * a bend where inner fibers would fold over gives one warning. Pieces (docs/tissue-models.md §9):
 * piece p of P holds the contiguous range [N·p/P, N·(p+1)/P) of the N fibers in output order
 * (global fiber ids, field data on every piece), so under MPI every rank lays only its own fibers.
 * The same properties give the same fibers.
 */
#ifndef vtkFiberBundleSource_h
#define vtkFiberBundleSource_h

#include "FiberPLIFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

class FIBERPLIFILTERS_EXPORT vtkFiberBundleSource : public vtkPolyDataAlgorithm
{
public:
  static vtkFiberBundleSource* New();
  vtkTypeMacro(vtkFiberBundleSource, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum ShapeType
  {
    CYLINDER = 0,
    TRAJECTORY = 1,
    CROSSING = 2,
    YSHAPE = 3,
    CHIASM = 4
  };
  enum RadiusDistributionType
  {
    LOGNORMAL = 0,
    UNIFORM = 1,
    GAMMA = 2,
    CONSTANT = 3
  };

  ///@{
  /**
   * Model: 0 Cylinder, 1 Trajectory (the polyline on input port 0), 2 Crossing, 3 YShape,
   * 4 Chiasm. Default is 0.
   */
  vtkSetMacro(Shape, int);
  vtkGetMacro(Shape, int);
  ///@}

  ///@{
  /**
   * Radius of each bundle in µm, >= FiberRadius. Default is 10.
   */
  vtkSetMacro(BundleRadius, double);
  vtkGetMacro(BundleRadius, double);
  ///@}

  ///@{
  /**
   * Length in µm: of the cylinder, of each crossing bundle or nerve (through the origin), or
   * trunk + branch of the Y-shape; not used for Trajectory. Default is 60.
   */
  vtkSetMacro(Length, double);
  vtkGetMacro(Length, double);
  ///@}

  ///@{
  /**
   * Nominal fiber radius in µm, > 0. Default is 0.8.
   */
  vtkSetMacro(FiberRadius, double);
  vtkGetMacro(FiberRadius, double);
  ///@}

  ///@{
  /**
   * Spread s of the fiber radii, >= 0 (0 = all radii equal; < 1 for Uniform). Default is 0.
   */
  vtkSetMacro(RadiusSpread, double);
  vtkGetMacro(RadiusSpread, double);
  ///@}

  ///@{
  /**
   * Radius distribution: 0 LogNormal (r·exp(s·z), median r), 1 Uniform (U[r(1-s), r(1+s)]),
   * 2 Gamma (mean r, coefficient of variation s: shape 1/s², scale r·s², truncated to
   * [r/4, 4r]), 3 Constant (every radius FiberRadius). Default is 0.
   */
  vtkSetMacro(RadiusDistribution, int);
  vtkGetMacro(RadiusDistribution, int);
  ///@}

  ///@{
  /**
   * Spacing of the triangular seed grid in µm, > 0; used when NumberOfFibers is 0. Default is 2.
   */
  vtkSetMacro(FiberSpacing, double);
  vtkGetMacro(FiberSpacing, double);
  ///@}

  ///@{
  /**
   * Fibers per bundle cross-section at random positions; 0 = triangular grid of FiberSpacing.
   * Default is 0.
   */
  vtkSetMacro(NumberOfFibers, int);
  vtkGetMacro(NumberOfFibers, int);
  ///@}

  ///@{
  /**
   * Distance of consecutive fiber points along the trajectory in µm, > 0. Default is 2.
   */
  vtkSetMacro(SegmentLength, double);
  vtkGetMacro(SegmentLength, double);
  ///@}

  ///@{
  /**
   * Maximum random displacement of every point per axis in µm (uniform in ±D), >= 0.
   * Default is 0.2.
   */
  vtkSetMacro(Displacement, double);
  vtkGetMacro(Displacement, double);
  ///@}

  ///@{
  /**
   * Angle in degrees: between the bundles (Crossing, up to 180), opening of the Y (YShape, below
   * 180), between the nerves (Chiasm, below 180). Default is 90.
   */
  vtkSetMacro(CrossingAngle, double);
  vtkGetMacro(CrossingAngle, double);
  ///@}

  ///@{
  /**
   * Chiasm: fraction of each nerve's fibers (the most lateral ones) that stay on their side,
   * 0 to 1. Default is 0.25.
   */
  vtkSetMacro(UncrossedFraction, double);
  vtkGetMacro(UncrossedFraction, double);
  ///@}

  ///@{
  /**
   * Distance of the nodes of Ranvier along each fiber in µm; 0 = off, -1 = shape default
   * (Chiasm 20 µm, other shapes off). Default is -1.
   */
  vtkSetMacro(RanvierSpacing, double);
  vtkGetMacro(RanvierSpacing, double);
  ///@}

  ///@{
  /**
   * Relative radius reduction at a node of Ranvier, 0 to 1 (exclusive). Default is 0.3.
   */
  vtkSetMacro(RanvierDepth, double);
  vtkGetMacro(RanvierDepth, double);
  ///@}

  ///@{
  /**
   * Length of a node of Ranvier in µm, > 0, at most half the RanvierSpacing. Default is 1.
   */
  vtkSetMacro(RanvierLength, double);
  vtkGetMacro(RanvierLength, double);
  ///@}

  ///@{
  /**
   * Seed of the random positions, radii, node phases and displacements; the same seed gives the
   * same fibers. Default is 42.
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

protected:
  vtkFiberBundleSource();
  ~vtkFiberBundleSource() override = default;
  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  int ExecutePiece(vtkInformationVector** inputVector, vtkInformationVector* outputVector);
  vtkFiberBundleSource(const vtkFiberBundleSource&) = delete;
  void operator=(const vtkFiberBundleSource&) = delete;

  int Shape = 0;
  double BundleRadius = 10.0;
  double Length = 60.0;
  double FiberRadius = 0.8;
  double RadiusSpread = 0.0;
  int RadiusDistribution = 0;
  double FiberSpacing = 2.0;
  int NumberOfFibers = 0;
  double SegmentLength = 2.0;
  double Displacement = 0.2;
  double CrossingAngle = 90.0;
  double UncrossedFraction = 0.25;
  double RanvierSpacing = -1.0;
  double RanvierDepth = 0.3;
  double RanvierLength = 1.0;
  int Seed = 42;
  double Tortuosity = 1.0;
  double UndulationWavelength = 20.0;
  double DispersionC2 = 1.0;
  double BeadingCV = 0.0;
  double BeadingLength = 5.0;
  double GRatio = 0.0;
  int GRatioModel = 0;
};

#endif
