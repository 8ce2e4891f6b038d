#include "vtkFiberWriter.h"

#include "FiberAdapter.h"
#include "FiberFieldData.h"
#include "FiberGuard.h"
#include "FiberH5Format.h"
#include "FiberInnerRadii.h"
#include "FiberPolyData.h"
#include "FiberProgress.h"
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
  // Any exception escaping the write becomes a VTK error (FiberGuard.h), never an abort; the
  // parallel writer reads it from LastWriteError.
  const int ok = fiberpli::GuardRequest(this, nullptr, fiberpli::ProxyName(this),
    [&]() -> int
    {
      const fiberpli::AbortScope abortScope(this); // an abort applies to this execution only
      this->SetErrorCode(vtkErrorCode::NoError);
      this->SetLastWriteError(nullptr);
      if (this->FileName == nullptr || this->FileName[0] == '\0')
      {
        this->Fail(vtkErrorCode::NoFileNameError, fiberpli::ProxyMessage(this, "no FileName set"));
        return 0;
      }
      const std::string path(this->FileName);
      vtkPolyData* input = vtkPolyData::SafeDownCast(this->GetInput());
      fiberpli::FiberConversion in =
        fiberpli::FiberPolyData::ToModel(input, fiberpli::ProxyName(this));
      if (!in.ok())
      {
        this->Fail(vtkErrorCode::UserError, in.error);
        return 0;
      }
      if (!in.warning.empty())
      {
        vtkWarningMacro(<< in.warning);
      }
      const std::string innerError =
        fiberpli::ReadInnerRadii(input, in, fiberpli::ProxyName(this)); // kept by .h5 and .csv
      if (!innerError.empty())
      {
        this->Fail(vtkErrorCode::UserError, innerError);
        return 0;
      }

      std::string ext = path.size() >= 3 ? path.substr(path.size() - 3) : "";
      std::transform(
        ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
      // The periodic cell goes where the format can hold it (.h5 attribute); the text formats have
      // no place for it.
      fiberpli::PeriodicCell cell;
      std::string cellError;
      fiberpli::ReadPeriodicCell(input, cell, cellError);
      if (!cellError.empty())
      {
        this->Fail(
          vtkErrorCode::UserError, fiberpli::ProxyMessage(this, "input field data " + cellError));
        return 0;
      }
      // CATERPillar .csv keeps the axon radius inside the outer one; CACTUS .txt the cell's edge.
      fiberpli::FiberFileExtras extras;
      extras.cell = cell;
      for (const fiberpli::Fiber& fiber : in.model.fibers)
      {
        if (!fiber.innerRadii.empty())
        {
          extras.innerRadii.resize(in.model.fibers.size());
          break;
        }
      }
      for (std::size_t f = 0; f < extras.innerRadii.size(); ++f)
      {
        extras.innerRadii[f] = in.model.fibers[f].innerRadii;
      }
      const std::string error = ext == ".h5" ? fiberpli::FiberH5Format::Write(path, in.model, cell)
                                             : fiberpli::writeFiberFile(path, in.model, &extras);
      if (!error.empty())
      {
        this->Fail(vtkErrorCode::CannotOpenFileError, fiberpli::ProxyMessage(this, error));
        return 0;
      }
      return 1;
    });
  if (!ok && this->GetErrorCode() == vtkErrorCode::NoError)
  {
    this->SetErrorCode(vtkErrorCode::UnknownError);
    this->SetLastWriteError("FiberWriter: writing failed (internal error)");
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
