/**
 * @class   vtkFiberSectionAlgorithm
 * @brief   base of the filters that image a section of a fiber model on the PLI pixel grid
 *
 * PLISimulation and FiberOrientationGroundTruth cut the same section out of the same fibers and
 * give images on the same pixel grid (docs/pli-simulation.md §3.1, §5.2; docs/pli-analysis.md §5),
 * so the section's properties, their meaning and the way a plan of the section is kept between
 * requests are written once, here: VolumeOfInterest, VoxelSize and PixelSize; fiber polydata on
 * input port 0, asked for as this rank's piece (FiberTileExchange.h); the volume a plan is made
 * for (the properties' volume, or the whole model's bounds for the sentinel); and the rule that a
 * plan holds until the properties or that volume change. A subclass plans in RequestInformation
 * and uses the plan in every RequestData, so its pixels always match WHOLE_EXTENT.
 */
#ifndef vtkFiberSectionAlgorithm_h
#define vtkFiberSectionAlgorithm_h

#include "FiberPLIFiltersModule.h" // for export macro
#include "vtkImageAlgorithm.h"

#include <memory> // for the fiber cache
#include <string> // for the bounds error

namespace fiberpli
{
class FiberModelCache;
}

class FIBERPLIFILTERS_EXPORT vtkFiberSectionAlgorithm : public vtkImageAlgorithm
{
public:
  vtkTypeMacro(vtkFiberSectionAlgorithm, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Section, µm: xmin xmax ymin ymax zmin zmax; the z range is the section's thickness. min > max
   * on every axis means the input's bounds (radii included). Default is (1, -1, 1, -1, 1, -1).
   */
  vtkSetVector6Macro(VolumeOfInterest, double);
  vtkGetVector6Macro(VolumeOfInterest, double);
  ///@}

  ///@{
  /**
   * Edge of a tissue voxel, µm, > 0 (else an error). Default is 0.4: half the default fiber
   * radius (0.8), the coarsest voxel that resolves the default fibers.
   */
  vtkSetMacro(VoxelSize, double);
  vtkGetMacro(VoxelSize, double);
  ///@}

  ///@{
  /**
   * Edge of a camera pixel (an output pixel), µm, >= VoxelSize (else an error). Default is 2.
   */
  vtkSetMacro(PixelSize, double);
  vtkGetMacro(PixelSize, double);
  ///@}

protected:
  vtkFiberSectionAlgorithm();
  ~vtkFiberSectionAlgorithm() override;
  /// Input port 0 takes fiber polydata (docs/data-contract.md §1).
  int FillInputPortInformation(int port, vtkInformation* info) override;
  /// Under MPI this rank's piece of fibers; RequestData receives those its tile reads.
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /// The time and volume a plan was made for.
  struct PlanStamp
  {
    vtkMTimeType time = 0;
    double volume[6] = { 1, -1, 1, -1, 1, -1 };
  };

  /// The volume to plan for: VolumeOfInterest, or for the sentinel the bounds (radii included) of
  /// the whole model. For the sentinel the input is brought up to date here with the piece
  /// RequestUpdateExtent asks for, so the data pass does not execute upstream again; under MPI the
  /// ranks' bounds are reduced, so every rank calls this on every information pass, planned already
  /// or not. Returns this rank's conversion error ("" when usable); `noFibers` is set when the
  /// sentinel met no fiber on any rank (`volume` then stays the sentinel).
  std::string VolumeToPlan(vtkInformationVector* inputVector, double volume[6], bool& noFibers);

  /// The stamp of a plan made now, for `volume`.
  PlanStamp StampFor(const double volume[6]);
  /// True when a plan with `stamp` is the plan of the current properties and `volume`.
  bool PlanHolds(const PlanStamp& stamp, const double volume[6]);

  /// The input's fibers, converted once per input MTime (docs/pli-simulation.md §7.3).
  std::unique_ptr<fiberpli::FiberModelCache> Fibers;

  double VolumeOfInterest[6] = { 1, -1, 1, -1, 1, -1 };
  double VoxelSize = 0.4;
  double PixelSize = 2.0;

private:
  vtkFiberSectionAlgorithm(const vtkFiberSectionAlgorithm&) = delete;
  void operator=(const vtkFiberSectionAlgorithm&) = delete;
};

#endif
