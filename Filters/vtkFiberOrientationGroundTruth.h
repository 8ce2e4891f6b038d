/**
 * @class   vtkFiberOrientationGroundTruth
 * @brief   orientation ground truth of a fiber model on the pixel grid of PLISimulation
 *
 * Input: fiber polydata (docs/data-contract.md §1). Output: a one-slice vtkImageData with the
 * geometry that PLISimulation gives for the same VolumeOfInterest, VoxelSize and PixelSize
 * (docs/pli-simulation.md §3.1, §5.2): n_a = round((max_a − min_a)/VoxelSize) voxels,
 * round(n·VoxelSize/PixelSize) pixels, origin (xmin + PixelSize/2, ymin + PixelSize/2, zmin +
 * n_z·VoxelSize/2), spacing PixelSize. Every voxel centre inside a fiber (nearest capsule axis,
 * distance <= the linearly tapered radius) gets the axis of the link that owns it; each pixel
 * summarises its voxels (all z) by the orientation tensor (docs/pli-analysis.md §5). Point arrays
 * (double): `direction` (degrees in [0, 180)), `inclination` (degrees in [0, 90]),
 * `inclination_signed` (degrees in [−90, 90]), `fraction` (tissue voxels / voxels of the pixel),
 * `anisotropy` (λ1 − λ2 of the tensor, 0 = no dominant axis). Pixels without tissue have NaN
 * angles. FiberOrientationMap colours the result. Invalid fibers, bad sizes or an empty volume give
 * an error naming the fiber or property.
 */
#ifndef vtkFiberOrientationGroundTruth_h
#define vtkFiberOrientationGroundTruth_h

#include "FiberPLIFiltersModule.h" // for export macro
#include "vtkFiberSectionAlgorithm.h"

#include <memory> // for the plan

class FIBERPLIFILTERS_EXPORT vtkFiberOrientationGroundTruth : public vtkFiberSectionAlgorithm
{
public:
  static vtkFiberOrientationGroundTruth* New();
  vtkTypeMacro(vtkFiberOrientationGroundTruth, vtkFiberSectionAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  // VolumeOfInterest, VoxelSize and PixelSize: the section, as PLISimulation's
  // (vtkFiberSectionAlgorithm).

  ///@{
  /**
   * Number of threads, 0 = all cores. The result does not depend on it. Default is 0.
   */
  vtkSetMacro(NumberOfThreads, int);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

protected:
  vtkFiberOrientationGroundTruth();
  ~vtkFiberOrientationGroundTruth() override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  /// This rank's part of RequestData (which makes its outcome collective under MPI).
  int ExecutePiece(vtkInformationVector**, vtkInformationVector*);

private:
  vtkFiberOrientationGroundTruth(const vtkFiberOrientationGroundTruth&) = delete;
  void operator=(const vtkFiberOrientationGroundTruth&) = delete;

  int NumberOfThreads = 0;
  /// The volume RequestInformation planned the image for (the input bounds when VolumeOfInterest is
  /// the sentinel): RequestData uses the same one, so its pixels always match WHOLE_EXTENT.
  double PlannedVolume[6] = { 1, -1, 1, -1, 1, -1 };
  /// The section of PlannedVolume and the sizes (Section/SectionPlan.h), planned once per change.
  struct SectionPlanned;
  std::unique_ptr<SectionPlanned> Plan;
  void PlanSection();
};

#endif
