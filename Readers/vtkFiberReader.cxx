#include "vtkFiberReader.h"

#include "FiberAdapter.h"
#include "FiberFieldData.h"
#include "FiberGuard.h"
#include "FiberH5Format.h"
#include "FiberInnerRadii.h"
#include "FiberPolyData.h"
#include "FiberProgress.h"
#include "IO/FiberFile.h"

#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cctype>
#include <new>

vtkStandardNewMacro(vtkFiberReader);

namespace
{
bool HasH5Extension(const std::string& path)
{
  if (path.size() < 3)
  {
    return false;
  }
  std::string ext = path.substr(path.size() - 3);
  std::transform(
    ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == ".h5";
}
} // namespace

//------------------------------------------------------------------------------
// Construct with no file name and DefaultRadius 1 µm.
vtkFiberReader::vtkFiberReader()
{
  this->SetNumberOfInputPorts(0);
}

//------------------------------------------------------------------------------
vtkFiberReader::~vtkFiberReader()
{
  this->SetFileName(nullptr);
  this->SetGroup(nullptr);
}

//------------------------------------------------------------------------------
int vtkFiberReader::CanReadFile(const char* fileName)
{
  if (fileName == nullptr)
  {
    return 0;
  }
  const std::string path(fileName);
  if (HasH5Extension(path))
  {
    return fiberpli::FiberH5Format::LooksLikeFiberH5(path) ? 1 : 0;
  }
  return fiberpli::canReadFiberFile(path) ? 1 : 0;
}

//------------------------------------------------------------------------------
int vtkFiberReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  // Any exception escaping the work becomes a VTK error (FiberGuard.h), never an abort.
  return fiberpli::GuardRequest(this, outputVector, fiberpli::ProxyName(this),
    [&]() -> int
    {
      const fiberpli::AbortScope abortScope(this); // an abort applies to this execution only
      vtkPolyData* output = vtkPolyData::GetData(outputVector);
      output->Initialize();
      if (this->FileName == nullptr || this->FileName[0] == '\0')
      {
        fiberpliErrorMacro(<< "no FileName set");
        return 0;
      }
      const std::string path(this->FileName);
      this->SetProgressText("Reading fibers");
      this->UpdateProgress(0.0);

      fiberpli::FiberReadResult result;
      fiberpli::PeriodicCell cell;
      // The readers check sizes before allocating; this is the last line against a crash.
      const bool inMemory = fiberpli::TryInMemory(
        [&]
        {
          if (HasH5Extension(path))
          {
            result.error = fiberpli::FiberH5Format::Read(
              path, this->Group ? this->Group : "", result.model, &cell);
            if (result.ok())
            {
              // .h5 files hold all points; validate like the text formats do.
              result.error = fiberpli::validateModel(result.model);
              if (!result.ok())
              {
                result.error = path + ": " + result.error;
              }
            }
          }
          else
          {
            result = fiberpli::readFiberFile(path, this->DefaultRadius);
          }
        });
      if (!inMemory)
      {
        result = fiberpli::FiberReadResult{};
        result.error = path + ": not enough memory to read the file";
      }
      if (!result.ok())
      {
        fiberpliErrorMacro(<< result.error);
        return 0;
      }
      if (result.droppedFibers > 0)
      {
        fiberpliWarningMacro(<< path << ": " << result.droppedFibers
                             << " fiber(s) with fewer than 2 points dropped");
      }
      for (const std::string& warning : result.warnings)
      {
        fiberpliWarningMacro(<< warning);
      }
      this->UpdateProgress(0.8);
      fiberpli::FiberPolyData::FromModel(result.model, output);
      fiberpli::AddInnerRadii(result.model, output); // .h5 and CATERPillar files can hold them
      if (cell.enabled())
      {
        fiberpli::AddPeriodicCell(output, cell);
      }
      if (result.boxSize != -1.0) // a CACTUS box (not a periodic cell); -1 is CACTUS's "none"
      {
        fiberpli::AddFieldDoubles(output, fiberpli::fiberfield::kBoxSize, { result.boxSize });
      }
      this->UpdateProgress(1.0);
      return 1;
    });
}

//------------------------------------------------------------------------------
void vtkFiberReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "Group: " << (this->Group ? this->Group : "(automatic)") << "\n";
  os << indent << "DefaultRadius: " << this->DefaultRadius << "\n";
}
