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
#include <cmath>
#include <sstream>
#include <vector>

vtkStandardNewMacro(vtkFiberWriter);

namespace
{
/// The field data box_size (one finite number, µm) into boxSize; absent: boxSize unchanged.
std::string ReadBoxSize(vtkPolyData* input, double& boxSize)
{
  vtkDataArray* box = fiberpli::FieldArray(input, fiberpli::fiberfield::kBoxSize);
  if (box == nullptr)
  {
    return {};
  }
  const std::vector<double> values = fiberpli::FieldValues(input, fiberpli::fiberfield::kBoxSize);
  if (values.size() != 1 || !std::isfinite(values[0]))
  {
    std::ostringstream msg;
    msg << "input field data " << fiberpli::fiberfield::kBoxSize
        << " must be one finite number (um), found " << values.size() << " value(s)";
    if (!values.empty())
    {
      msg << " starting with " << fiberpli::formatNumber(values[0]);
    }
    return msg.str();
  }
  boxSize = values[0];
  return {};
}
} // namespace

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
      // CATERPillar .csv keeps the axon radii (Fiber::innerRadii); CACTUS .txt the cell's largest
      // edge or, without a cell, the box size a strand list was read with.
      fiberpli::FiberFileExtras extras;
      extras.cell = cell;
      const std::string boxError = ReadBoxSize(input, extras.boxSize);
      if (!boxError.empty())
      {
        this->Fail(vtkErrorCode::UserError, fiberpli::ProxyMessage(this, boxError));
        return 0;
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
