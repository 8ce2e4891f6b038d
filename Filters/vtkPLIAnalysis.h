/**
 * @class   vtkPLIAnalysis
 * @brief   3D-PLI analysis: polarizer stack → transmittance, direction, retardation, inclination
 *
 * Input: a one-slice vtkImageData as written by PLISimulation (docs/pli-simulation.md §7): point
 * array `intensity` (N >= 3 components, one per polarizer angle), optionally tilted views
 * `intensity_tilt_0..M−1` (same N); field data `polarizer_angles` (degrees; when missing, N
 * equidistant angles k·180°/N), `tilt_angles` and `tilt_directions` (degrees, in-tissue tilt and
 * azimuth of every tilted view; older data: one `tilt_angle` and azimuths 0°, 90°, 180°, 270° for
 * four views), `tilt_convention` (0 Physical, 1 FastPLI) and `noise_gain`. Any polarimeter set-up
 * of PLISimulation is analysed without further settings. Output: the input geometry with the point
 * arrays (double) `transmittance` (2·a0, intensity units), `direction` (degrees in [0, 180),
 * in-plane fiber axis counter-clockwise from +x), `retardation` (|sin δ| in [0, 1]), `inclination`
 * (degrees in [0, 90]); with the tilt fit also `inclination_signed` (degrees in [−90, 90]),
 * `relative_thickness` and `fit_chi2` (docs/pli-analysis.md §1–§3). Input arrays are not passed.
 * Pixels with a0 <= 0 or non-finite data are NaN in every output. Field data
 * `reference_retardation` and `inclination_method` (1 Retardation, 2 Tilt) report what was used.
 *
 * The retardation-based inclination is unsigned and valid only while the in-plane relative
 * thickness t_rel = 4·d·|Δn|/λ <= 1 (sin δ must be monotonic). Sub-extents are supported; the
 * automatic ReferenceRetardation is the maximum over the whole data set under MPI (AllReduce MAX).
 * Errors (no `intensity` array, fewer than 3 angles, component count differs from the number of
 * angles, angles that do not determine the harmonic, tilt fit without tilt stacks) name the
 * array or property and leave an empty output.
 */
#ifndef vtkPLIAnalysis_h
#define vtkPLIAnalysis_h

#include "FiberPLIFiltersModule.h" // for export macro
#include "vtkImageAlgorithm.h"

class FIBERPLIFILTERS_EXPORT vtkPLIAnalysis : public vtkImageAlgorithm
{
public:
  static vtkPLIAnalysis* New();
  vtkTypeMacro(vtkPLIAnalysis, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum InclinationMethods
  {
    AUTO = 0,        ///< TILT when at least 2 tilted views with tilt > 0 exist, else RETARDATION
    RETARDATION = 1, ///< unsigned inclination from the retardation (docs/pli-analysis.md §3.1)
    TILT = 2         ///< signed inclination from the tilt fit (§3.2)
  };

  ///@{
  /**
   * How the inclination is computed: 0 Auto (Tilt when at least two `intensity_tilt_v` arrays
   * with a tilt > 0 exist, else Retardation), 1 Retardation, 2 Tilt; other values are an error.
   * Default is 0 (Auto).
   */
  vtkSetMacro(InclinationMethod, int);
  vtkGetMacro(InclinationMethod, int);
  ///@}

  ///@{
  /**
   * Retardation of an in-plane fiber, used by the Retardation method, 0 to 1. 0 = automatic: the
   * largest retardation of the image (global under MPI). Outside [0, 1] is an error. Default is 0.
   */
  vtkSetMacro(ReferenceRetardation, double);
  vtkGetMacro(ReferenceRetardation, double);
  ///@}

  ///@{
  /**
   * Camera gain g of the tilt-fit weights; −1 = field data `noise_gain` if present, else 3;
   * 0 = noise-free data (weights of g = 1). −1 or 0 to 1e6, other values are an error. Default is
   * −1.
   */
  vtkSetMacro(NoiseGain, double);
  vtkGetMacro(NoiseGain, double);
  ///@}

  ///@{
  /**
   * Number of threads, 0 = all cores. The result does not depend on it. Default is 0.
   */
  vtkSetMacro(NumberOfThreads, int);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

protected:
  vtkPLIAnalysis();
  ~vtkPLIAnalysis() override = default;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  /// This rank's analysis (errors reported with vtkErrorMacro, 0 returned); `reduced` is set when
  /// it took part in the reduction of the reference retardation.
  int ExecutePiece(
    vtkInformationVector** inputVector, vtkInformationVector* outputVector, bool& reduced);

private:
  vtkPLIAnalysis(const vtkPLIAnalysis&) = delete;
  void operator=(const vtkPLIAnalysis&) = delete;

  int InclinationMethod = AUTO;
  double ReferenceRetardation = 0.0;
  double NoiseGain = -1.0;
  int NumberOfThreads = 0;
};

#endif
