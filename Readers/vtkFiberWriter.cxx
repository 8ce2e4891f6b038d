#include "vtkFiberWriter.h"

#include "FiberFieldData.h"
#include "FiberProgress.h"
#include "FiberH5Format.h"
#include "FiberPolyData.h"
#include "IO/FiberFile.h"

#include <vtkDataArray.h>
#include <vtkErrorCode.h>
#include <vtkPointData.h>
#include <vtkInformation.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cctype>

vtkStandardNewMacro(vtkFiberWriter);


//------------------------------------------------------------------------------
vtkFiberWriter::~vtkFiberWriter()
{
  this->SetFileName(nullptr);
  this->SetLastWriteError(nullptr);
}

//------------------------------------------------------------------------------
int vtkFiberWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

//------------------------------------------------------------------------------
void vtkFiberWriter::WriteData()
{
  const fiberpli::AbortScope abortScope(this); // an abort applies to this execution only
  this->SetErrorCode(vtkErrorCode::NoError);
  this->SetLastWriteError(nullptr);
  if (this->FileName == nullptr || this->FileName[0] == '\0')
  {
    this->Fail(vtkErrorCode::NoFileNameError, "FiberWriter: no FileName set");
    return;
  }
  const std::string path(this->FileName);
  vtkPolyData* input = vtkPolyData::SafeDownCast(this->GetInput());
  fiberpli::FiberConversion in = fiberpli::FiberPolyData::ToModel(input, "FiberWriter");
  if (!in.ok())
  {
    this->Fail(vtkErrorCode::UserError, in.error);
    return;
  }
  if (!in.warning.empty())
  {
    vtkWarningMacro(<< in.warning);
  }

  std::string ext = path.size() >= 3 ? path.substr(path.size() - 3) : "";
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  // The periodic cell goes where the format can hold it (.h5 attribute); the text formats have no
  // place for it.
  fiberpli::PeriodicCell cell;
  std::string cellError;
  fiberpli::ReadPeriodicCell(input, cell, cellError);
  if (!cellError.empty())
  {
    this->Fail(vtkErrorCode::UserError, "FiberWriter: input field data " + cellError);
    return;
  }
  // CATERPillar .csv keeps the axon radius inside the outer one; CACTUS .txt the cell's edge.
  fiberpli::FiberFileExtras extras;
  extras.cell = cell;
  if (vtkDataArray* inner = input->GetPointData()->GetArray("inner_radius"))
  {
    extras.innerRadii.resize(in.model.fibers.size());
    for (std::size_t f = 0; f < in.sourcePoints.size(); ++f)
    {
      for (long long id : in.sourcePoints[f])
      {
        extras.innerRadii[f].push_back(inner->GetTuple1(static_cast<vtkIdType>(id)));
      }
    }
  }
  const std::string error = ext == ".h5" ? fiberpli::FiberH5Format::Write(path, in.model, cell)
                                         : fiberpli::writeFiberFile(path, in.model, &extras);
  if (!error.empty())
  {
    this->Fail(vtkErrorCode::CannotOpenFileError, "FiberWriter: " + error);
  }
}

//------------------------------------------------------------------------------
void vtkFiberWriter::Fail(unsigned long code, const std::string& message)
{
  vtkErrorMacro(<< message);
  this->SetErrorCode(code);
  this->SetLastWriteError(message.c_str());
}

//------------------------------------------------------------------------------
void vtkFiberWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
}
