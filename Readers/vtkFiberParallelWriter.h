/**
 * @class   vtkFiberParallelWriter
 * @brief   ParaView's parallel-serial writer for vtkFiberWriter, failing on every rank together
 *
 * vtkParallelSerialWriter gathers the fibers of all ranks to the first rank, which writes one
 * file with the inner vtkFiberWriter. Alone it reports a failed write (invalid gathered fibers,
 * full disk) only on the writing rank. This subclass makes the outcome collective
 * (FiberCollective.h): every rank reports the error of the write, and a rank whose own error
 * stopped the pipeline before the gather makes no rank write (the existing file is kept).
 */
#ifndef vtkFiberParallelWriter_h
#define vtkFiberParallelWriter_h

#include "FiberPLIReadersModule.h" // for export macro
#include "vtkParallelSerialWriter.h"

class FIBERPLIREADERS_EXPORT vtkFiberParallelWriter : public vtkParallelSerialWriter
{
public:
  static vtkFiberParallelWriter* New();
  vtkTypeMacro(vtkFiberParallelWriter, vtkParallelSerialWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkFiberParallelWriter() = default;
  ~vtkFiberParallelWriter() override = default;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

private:
  vtkFiberParallelWriter(const vtkFiberParallelWriter&) = delete;
  void operator=(const vtkFiberParallelWriter&) = delete;
};

#endif
