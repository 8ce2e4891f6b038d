/**
 * @class   vtkFiberWriter
 * @brief   writes fiber polydata as fastPLI .dat or .h5, or MRtrix .tck, never destroying a file
 *
 * Input: fiber polydata (docs/data-contract.md §1), validated like every filter's input. The format
 * is chosen by the extension of FileName. The file is written to a temporary file beside the target
 * and renamed over it, so a failed write leaves an existing file intact. .dat and .h5 keep points,
 * radii and the grouping into bundles (by bundle_id); .tck keeps the points (float32) and writes
 * the radii into the MRtrix track-scalar file `<name>.radius.tsf` beside it. Errors name the file.
 */
#ifndef vtkFiberWriter_h
#define vtkFiberWriter_h

#include "FiberPLIReadersModule.h" // for export macro
#include "vtkWriter.h"

#include <string> // for Fail

class vtkPolyData;

class FIBERPLIREADERS_EXPORT vtkFiberWriter : public vtkWriter
{
public:
  static vtkFiberWriter* New();
  vtkTypeMacro(vtkFiberWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The file to write (.dat, .h5 or .tck). Default is none.
   */
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

  ///@{
  /**
   * The error message of the last Write(), nullptr after a success. vtkFiberParallelWriter
   * reports it on every rank.
   */
  vtkSetStringMacro(LastWriteError);
  vtkGetStringMacro(LastWriteError);
  ///@}

protected:
  vtkFiberWriter() = default;
  ~vtkFiberWriter() override;
  int FillInputPortInformation(int port, vtkInformation* info) override;
  void WriteData() override;

private:
  vtkFiberWriter(const vtkFiberWriter&) = delete;
  void operator=(const vtkFiberWriter&) = delete;

  /// Reports `message`, sets the error code and LastWriteError.
  void Fail(unsigned long code, const std::string& message);

  char* FileName = nullptr;
  char* LastWriteError = nullptr;
};

#endif
