/**
 * @class   vtkFiberFieldSource
 * @brief   fills the region of a 3-D orientation field, or around guide lines, with fibers that
 * follow it
 *
 * Input: a vtkImageData with a 3-component point array, the fiber axis at every grid point, or a
 * cell array, the axis at every cell centre (its sign does not matter; a zero vector marks an empty
 * point where no fiber goes; NaN vectors count as empty, with a warning). It is input array 0
 * (SetInputArrayToProcess; in ParaView the property OrientationArray). An optional second array
 * (input array 1, SecondOrientationArray) is a second, crossing population; a 6-component
 * OrientationArray holds both populations in one array (components 0-2 and 3-5, a zero triple =
 * that population absent there), exactly as the two halves given as two arrays. Or: a vtkPolyData
 * of guide lines (e.g. tractography streamlines read from a .tck file): its line cells are
 * rasterised into the field on a grid of GuideSpacing covering the guides padded by GuideRadius
 * (docs/field-source.md §7; one population, or one per bundle_id value with GuidePopulations
 * ByBundle); the array selections are then not used. Output: fiber
 * polydata (docs/data-contract.md §1): one polyline per fiber, point array `radius` (µm; with
 * GRatio > 0 also `inner_radius`), cell arrays `fiber_id` and `bundle_id` (the index of the field
 * the fiber follows), field data `segment_length`, `seed` and `traced_volume_fraction` (the Σ π r²
 * · length reached over the non-empty volume). Seeds are uniform over the non-empty part of the
 * region, every fiber is traced both ways with RK2 or RK4 steps of SegmentLength and ends on the
 * region's boundary or the mask's edge (docs/field-source.md). Fibers are added until
 * VolumeFraction is reached, or NumberOfFibers when that is > 0. Identical input and properties
 * give identical output. Invalid properties or input give an error naming them and an empty output.
 * Pieces: piece p of P holds the contiguous range [N·p/P, N·(p+1)/P) of the N fibers (every piece
 * traces all of them from the whole field, so the pieces in order are the serial output).
 */
#ifndef vtkFiberFieldSource_h
#define vtkFiberFieldSource_h

#include "FiberPLIFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

class FIBERPLIFILTERS_EXPORT vtkFiberFieldSource : public vtkPolyDataAlgorithm
{
public:
  static vtkFiberFieldSource* New();
  vtkTypeMacro(vtkFiberFieldSource, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Target fiber volume fraction in (0, 0.9]: Σ π r² · length over the volume where the field is
   * not empty; fibers are added until it is reached. Default is 0.3.
   */
  vtkSetMacro(VolumeFraction, double);
  vtkGetMacro(VolumeFraction, double);
  ///@}

  ///@{
  /**
   * > 0: make exactly this many fibers (VolumeFraction is then ignored); 0 = use VolumeFraction.
   * Default is 0.
   */
  vtkSetMacro(NumberOfFibers, int);
  vtkGetMacro(NumberOfFibers, int);
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
   * Spread s of the fiber radii, >= 0 (0 = all radii FiberRadius). Default is 0.
   */
  vtkSetMacro(RadiusSpread, double);
  vtkGetMacro(RadiusSpread, double);
  ///@}

  ///@{
  /**
   * Radius distribution: 0 LogNormal, 1 Uniform, 2 Gamma, 3 Constant (as in FiberCubeSource).
   * Default is 3 (Constant).
   */
  vtkSetMacro(RadiusDistribution, int);
  vtkGetMacro(RadiusDistribution, int);
  ///@}

  ///@{
  /**
   * Distance of consecutive fiber points in µm (the integration step), > 0. Default is 2.
   */
  vtkSetMacro(SegmentLength, double);
  vtkGetMacro(SegmentLength, double);
  ///@}

  ///@{
  /**
   * Integration scheme: 0 RK2 (midpoint), 1 RK4 (classical Runge–Kutta). Default is 1.
   */
  vtkSetMacro(IntegrationScheme, int);
  vtkGetMacro(IntegrationScheme, int);
  ///@}

  ///@{
  /**
   * Longest fiber in µm, >= 0; 0 = automatic (4 × the region's diagonal). Ends fibers in closed
   * fields. Default is 0.
   */
  vtkSetMacro(MaxFiberLength, double);
  vtkGetMacro(MaxFiberLength, double);
  ///@}

  ///@{
  /**
   * Relative shares of the first and second field's populations (of the fiber volume, or of the
   * count with NumberOfFibers), each > 0. Used only with a second array. Default is 1, 1.
   */
  vtkSetVector2Macro(PopulationShares, double);
  vtkGetVector2Macro(PopulationShares, double);
  ///@}

  ///@{
  /**
   * Coefficient of variation of the radius along each fiber, 0 to 1 (0 = off): a smooth log-normal
   * profile whose mean over the fiber's points is its radius (docs/tissue-models.md §10.3).
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
   * g-ratio model with myelin on: 0 = Constant (inner = GRatio · outer), 1 = Lee2019. Default is 0.
   */
  vtkSetMacro(GRatioModel, int);
  vtkGetMacro(GRatioModel, int);
  ///@}

  ///@{
  /**
   * Seed of the random seeding and radii; the same seed gives the same fibers. Default is 42.
   */
  vtkSetMacro(Seed, int);
  vtkGetMacro(Seed, int);
  ///@}

  ///@{
  /**
   * Candidate lines per fiber, in [1, 64]: each fiber keeps, of this many traced seeds, the line
   * that overlaps the fibers placed before it least, so dense models start with fewer collisions.
   * 1 = the first seed, as drawn. Default is 1.
   */
  vtkSetMacro(SeedCandidates, int);
  vtkGetMacro(SeedCandidates, int);
  ///@}

  ///@{
  /**
   * Guide lines (a vtkPolyData input): how far a guide reaches, in µm, > 0. A grid point within
   * GuideRadius of a guide segment takes the principal axis of the length-weighted orientation
   * tensor of the segments within that distance; farther points are empty. Default is 5.
   */
  vtkSetMacro(GuideRadius, double);
  vtkGetMacro(GuideRadius, double);
  ///@}

  ///@{
  /**
   * Guide lines: the spacing in µm of the grid the guides are rasterised on, in (0, GuideRadius].
   * The grid covers the guides' bounds padded by GuideRadius. Default is 1.
   */
  vtkSetMacro(GuideSpacing, double);
  vtkGetMacro(GuideSpacing, double);
  ///@}

  ///@{
  /**
   * Guide lines: 0 One (all guides one population, bundle_id 0) or 1 ByBundle (the guides of each
   * value of their bundle_id cell array make one population, at most two; the smaller value gets
   * bundle_id 0). Default is 0.
   */
  vtkSetMacro(GuidePopulations, int);
  vtkGetMacro(GuidePopulations, int);
  ///@}

  ///@{
  /**
   * Threads for rasterising guide lines and tracing candidate lines, 0 = all cores; the result
   * does not depend on it.
   * Default is 0.
   */
  vtkSetMacro(NumberOfThreads, int);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

protected:
  vtkFiberFieldSource();
  ~vtkFiberFieldSource() override = default;
  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  int Execute(vtkInformationVector** inputVector, vtkInformationVector* outputVector);

  vtkFiberFieldSource(const vtkFiberFieldSource&) = delete;
  void operator=(const vtkFiberFieldSource&) = delete;

  double VolumeFraction = 0.3;
  int NumberOfFibers = 0;
  double FiberRadius = 0.8;
  double RadiusSpread = 0.0;
  int RadiusDistribution = 3;
  double SegmentLength = 2.0;
  int IntegrationScheme = 1;
  double MaxFiberLength = 0.0;
  double PopulationShares[2] = { 1.0, 1.0 };
  double BeadingCV = 0.0;
  double BeadingLength = 5.0;
  double GRatio = 0.0;
  int GRatioModel = 0;
  int Seed = 42;
  int SeedCandidates = 1;
  double GuideRadius = 5.0;
  double GuideSpacing = 1.0;
  int GuidePopulations = 0;
  int NumberOfThreads = 0;
};

#endif
