/**
 * @class   vtkFiberOrientationMap
 * @brief   direction + inclination → RGB fiber orientation map (FOM) and its colour legend
 *
 * Input: vtkImageData with a direction and an inclination point array (degrees; any numeric type,
 * read without a copy when it is a one-component double array; the sign of the inclination is
 * ignored), e.g. from PLIAnalysis or FiberOrientationGroundTruth. They are the input arrays to
 * process 0 and 1 (SetInputArrayToProcess; by default the arrays named `direction` and
 * `inclination`; in ParaView the properties DirectionArray and InclinationArray).
 * Output port 0: the input with the point array `fom` (unsigned char, 3 components) added and set
 * as active scalars; NaN pixels are black. Output port 1: the colour legend, a LegendSize ×
 * LegendSize image of the upper hemisphere seen from +z (centre = fiber along z, rim = in-plane
 * fibers, direction = angle around the centre) with the same `fom` array, white outside the disc,
 * spanning [−1, 1]² (docs/pli-analysis.md §4). Schemes: HSV-black (hue = 2·direction, value =
 * 1 − |inclination|/90) and RGB (|x|, |y|, |z| of the fiber axis). With a Mask, background
 * pixels — retardation below the fraction MaskThreshold of the image's largest, or transmittance
 * within that fraction of the image's largest — are black and the point
 * array `mask` (unsigned char, 1 = shown, 0 = background) is added. A missing array is an error
 * naming it.
 */
#ifndef vtkFiberOrientationMap_h
#define vtkFiberOrientationMap_h

#include "FiberPLIFiltersModule.h" // for export macro
#include "vtkImageAlgorithm.h"

class FIBERPLIFILTERS_EXPORT vtkFiberOrientationMap : public vtkImageAlgorithm
{
public:
  static vtkFiberOrientationMap* New();
  vtkTypeMacro(vtkFiberOrientationMap, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum ColorSchemes
  {
    HSV_BLACK = 0,
    RGB = 1
  };

  ///@{
  /**
   * Colour scheme: 0 HSV-black, 1 RGB. Default is 0 (HSV-black).
   */
  vtkSetMacro(ColorScheme, int); // checked at execution: out of range is an error
  vtkGetMacro(ColorScheme, int);
  ///@}

  enum Masks
  {
    MASK_NONE = 0,
    MASK_RETARDATION = 1,
    MASK_TRANSMITTANCE = 2
  };

  ///@{
  /**
   * Background mask: 0 none, 1 by retardation (pixels with retardation below MaskThreshold × the
   * image's largest retardation are black), 2 by transmittance (pixels with transmittance above
   * (1 − MaskThreshold) × the image's largest transmittance are black). Default is 0.
   */
  vtkSetMacro(Mask, int); // checked at execution
  vtkGetMacro(Mask, int);
  ///@}

  ///@{
  /**
   * Threshold of the mask as a fraction in [0, 1] of the image's largest value of the masked
   * array (over all pieces of a split image): how close to empty background a pixel must be to
   * be shown black. The absolute value used goes to field data mask_threshold. Default is 0.07.
   */
  vtkSetMacro(MaskThreshold, double);
  vtkGetMacro(MaskThreshold, double);
  ///@}

  ///@{
  /**
   * Width and height of the legend image (output port 1) in pixels, 1 to 16384. Default is 256.
   */
  vtkSetMacro(LegendSize, int); // checked by the Core (fomLegend)
  vtkGetMacro(LegendSize, int);
  ///@}

  ///@{
  /**
   * Number of threads, 0 = all cores. Default is 0.
   */
  vtkSetMacro(NumberOfThreads, int);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

protected:
  vtkFiberOrientationMap();
  ~vtkFiberOrientationMap() override = default;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  /// RequestData of this rank's piece; sets `reduced` once it made the mask's one collective call.
  int ExecutePiece(
    vtkInformationVector** inputVector, vtkInformationVector* outputVector, bool& reduced);

  vtkFiberOrientationMap(const vtkFiberOrientationMap&) = delete;
  void operator=(const vtkFiberOrientationMap&) = delete;

  int ColorScheme = HSV_BLACK;
  int LegendSize = 256;
  int Mask = MASK_NONE;
  double MaskThreshold = 0.07;
  int NumberOfThreads = 0;
};

#endif
