#include "vtkFiberWriter.h"

#include "FiberProgress.h"
#include "FiberH5Format.h"
#include "FiberPolyData.h"
#include "IO/FiberFile.h"

#include <vtkErrorCode.h>
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
  if (this->FileName == nullptr || this->FileName[0] == '\0')
  {
    vtkErrorMacro(<< "FiberWriter: no FileName set");
    this->SetErrorCode(vtkErrorCode::NoFileNameError);
    return;
  }
  const std::string path(this->FileName);
  vtkPolyData* input = vtkPolyData::SafeDownCast(this->GetInput());
  fiberpli::FiberConversion in = fiberpli::FiberPolyData::ToModel(input, "FiberWriter");
  if (!in.ok())
  {
    vtkErrorMacro(<< in.error);
    this->SetErrorCode(vtkErrorCode::UserError);
    return;
  }
  if (!in.warning.empty())
  {
    vtkWarningMacro(<< in.warning);
  }

  std::string ext = path.size() >= 3 ? path.substr(path.size() - 3) : "";
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  const std::string error = ext == ".h5" ? fiberpli::FiberH5Format::Write(path, in.model) : fiberpli::writeFiberFile(path, in.model);
  if (!error.empty())
  {
    vtkErrorMacro(<< "FiberWriter: " << error);
    this->SetErrorCode(vtkErrorCode::CannotOpenFileError);
  }
}

//------------------------------------------------------------------------------
void vtkFiberWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
}
