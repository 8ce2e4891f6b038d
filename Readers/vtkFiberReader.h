/**
 * @class   vtkFiberReader
 * @brief   reads fiber files: fastPLI .dat and .h5, MRtrix .tck, TrackVis .trk
 *
 * Output: fiber polydata (docs/data-contract.md §1): one polyline per fiber, point array `radius`
 * (µm), cell arrays `fiber_id` (position of the fiber in the file) and `bundle_id` (bundle of
 * .dat/.h5 files, 0 for .tck/.trk). The format is chosen by the extension; CanReadFile looks at the
 * content, so other files with these extensions (Tecplot .dat, CONVERGE .h5, …) are left to their
 * readers. A .tck file takes its radii from the MRtrix track-scalar file `<name>.radius.tsf` beside
 * it when there is one (it must match the tracks); otherwise, and for .trk, every point gets
 * DefaultRadius. A file that is not what it claims gives an error naming the file and the line or
 * byte offset, and an empty output. Fibers of fewer than 2 points are dropped with one warning. In
 * a distributed run the fibers are read on piece 0 only.
 */
#ifndef vtkFiberReader_h
#define vtkFiberReader_h

#include "FiberPLIReadersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

class FIBERPLIREADERS_EXPORT vtkFiberReader : public vtkPolyDataAlgorithm
{
public:
  static vtkFiberReader* New();
  vtkTypeMacro(vtkFiberReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The file to read (.dat, .h5, .tck or .trk). Default is none.
   */
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

  ///@{
  /**
   * Radius in µm given to every point of files that store none (.trk, .tck without .radius.tsf), >
   * 0. Default is 1.
   */
  vtkSetMacro(DefaultRadius, double);
  vtkGetMacro(DefaultRadius, double);
  ///@}

  ///@{
  /**
   * .h5 only: the HDF5 group holding the bundles (fastPLI's `save(..., group_name=...)`), e.g.
   * "fiber_bundles" or "/model/fibers". Empty (the default) means found automatically: the root
   * or the one group holding bundles; several such groups are an error listing them.
   */
  vtkSetStringMacro(Group);
  vtkGetStringMacro(Group);
  ///@}

  /**
   * 1 when the file has one of our extensions and its content is of that format, else 0.
   */
  int CanReadFile(const char* fileName);

protected:
  vtkFiberReader();
  ~vtkFiberReader() override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkFiberReader(const vtkFiberReader&) = delete;
  void operator=(const vtkFiberReader&) = delete;

  char* FileName = nullptr;
  char* Group = nullptr;
  double DefaultRadius = 1.0;
};

#endif
