#include "vtkFiberMeshWriter.h"

#include "FiberAdapter.h"
#include "FiberFieldData.h"
#include "FiberGuard.h"
#include "FiberInnerRadii.h"
#include "FiberPolyData.h"
#include "FiberProgress.h"
#include "IO/AtomicFile.h"
#include "IO/McdcCylinders.h"
#include "Mesh/SubstrateMesher.h"
#include "Util/NumberFormat.h"
#include "Util/ValueCheck.h"

#include <vtkDataArray.h>
#include <vtkErrorCode.h>
#include <vtkInformation.h>
#include <vtkLogger.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <cmath>
#include <sstream>

#include <sys/stat.h>

vtkStandardNewMacro(vtkFiberMeshWriter);

namespace
{
/// The path without its extension: "dir/cell.ply" -> "dir/cell" (the name of the files beside it).
std::string Stem(const std::string& path)
{
  const std::size_t dot = path.find_last_of('.');
  const std::size_t slash = path.find_last_of('/');
  return dot != std::string::npos && (slash == std::string::npos || dot > slash)
    ? path.substr(0, dot)
    : path;
}
} // namespace

//------------------------------------------------------------------------------
vtkFiberMeshWriter::~vtkFiberMeshWriter()
{
  this->SetFileName(nullptr);
}

//------------------------------------------------------------------------------
int vtkFiberMeshWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

//------------------------------------------------------------------------------
void vtkFiberMeshWriter::WriteData()
{
  // Any exception escaping the write becomes a VTK error (FiberGuard.h), never an abort.
  const int ok = fiberpli::GuardRequest(this, nullptr, fiberpli::ProxyName(this),
    [&]() -> int
    {
      this->WriteMesh();
      return 1;
    });
  if (!ok && this->GetErrorCode() == vtkErrorCode::NoError)
  {
    this->SetErrorCode(vtkErrorCode::UnknownError);
  }
}

//------------------------------------------------------------------------------
void vtkFiberMeshWriter::WriteMesh()
{
  const fiberpli::AbortScope abortScope(this);
  this->SetErrorCode(vtkErrorCode::NoError);
  this->VerticesWritten = this->TrianglesWritten = this->BytesWritten = 0.0;
  if (this->FileName == nullptr || this->FileName[0] == '\0')
  {
    this->Fail(vtkErrorCode::NoFileNameError, fiberpli::ProxyMessage(this, "no FileName set"));
    return;
  }
  const std::string path(this->FileName);
  if (!(this->Tolerance >= 0.0) || !std::isfinite(this->Tolerance))
  {
    this->Fail(vtkErrorCode::UserError,
      fiberpli::ProxyMessage(this,
        fiberpli::mustBe(
          "Tolerance", this->Tolerance, "finite and >= 0 (0: use NumberOfSides)", "µm")));
    return;
  }
  fiberpli::McdcCylinderList listKind = fiberpli::McdcCylinderList::ZAligned;
  int kind = CYLINDERS_NONE;
  const std::string badKind = fiberpli::enumFromCode(this->CylinderList, CYLINDERS_ORIENTED,
    "CylinderList", "0 (None), 1 (cylinders_list) or 2 (oriented_cylinders_list)", kind);
  if (!badKind.empty())
  {
    this->Fail(vtkErrorCode::UserError, fiberpli::ProxyMessage(this, badKind));
    return;
  }
  listKind = kind == CYLINDERS_ORIENTED ? fiberpli::McdcCylinderList::Oriented
                                        : fiberpli::McdcCylinderList::ZAligned;
  if (kind != CYLINDERS_NONE &&
    (!(this->StraightnessTolerance >= 0.0) || !std::isfinite(this->StraightnessTolerance)))
  {
    this->Fail(vtkErrorCode::UserError,
      fiberpli::ProxyMessage(this,
        fiberpli::mustBe(
          "StraightnessTolerance", this->StraightnessTolerance, "finite and >= 0", "µm")));
    return;
  }
  vtkPolyData* input = vtkPolyData::SafeDownCast(this->GetInput());
  fiberpli::FiberConversion in = fiberpli::FiberPolyData::ToModel(input, fiberpli::ProxyName(this));
  if (!in.ok())
  {
    this->Fail(vtkErrorCode::UserError, in.error);
    return;
  }
  if (!in.warning.empty())
  {
    vtkWarningMacro(<< in.warning);
  }
  fiberpli::PeriodicCell cell;
  std::string cellError;
  fiberpli::ReadPeriodicCell(input, cell, cellError);
  if (!cellError.empty())
  {
    this->Fail(
      vtkErrorCode::UserError, fiberpli::ProxyMessage(this, "input field data " + cellError));
    return;
  }
  // The axon surfaces: inner_radius checked and read by the one rule of FiberInnerRadii.h.
  const std::string innerError = fiberpli::ReadInnerRadii(input, in, fiberpli::ProxyName(this));
  if (!innerError.empty())
  {
    this->Fail(vtkErrorCode::UserError, innerError);
    return;
  }
  std::vector<std::vector<double>> inner;
  for (std::size_t f = 0; this->InnerSurfaces && f < in.model.fibers.size(); ++f)
  {
    if (!in.model.fibers[f].innerRadii.empty())
    {
      inner.resize(in.model.fibers.size());
      inner[f] = in.model.fibers[f].innerRadii;
    }
  }
  fiberpli::SubstrateMeshOptions options;
  options.sides = this->NumberOfSides;
  options.ringSpacing = this->RingSpacing;
  if (this->Tolerance > 0.0)
  {
    options.sides =
      fiberpli::substrateSidesForTolerance(fiberpli::largestRadius(in.model), this->Tolerance);
  }
  const std::string bad = fiberpli::checkSubstrateMeshOptions(options);
  if (!bad.empty())
  {
    this->Fail(vtkErrorCode::UserError, fiberpli::ProxyMessage(this, bad));
    return;
  }
  // The cylinder list is made (one line per fiber) before any file is touched: a fiber that is not
  // straight refuses the whole write, naming it, and leaves existing files as they are.
  std::string cylinders;
  if (kind != CYLINDERS_NONE)
  {
    std::ostringstream list;
    const std::string listError =
      fiberpli::writeMcdcCylinders(list, in.model, listKind, this->StraightnessTolerance);
    if (!listError.empty())
    {
      this->Fail(
        vtkErrorCode::UserError, fiberpli::ProxyMessage(this, "CylinderList: " + listError));
      return;
    }
    cylinders = list.str();
  }
  this->SetProgressText("Writing the substrate mesh");
  fiberpli::SubstrateMeshCounts counts;
  fiberpli::Status status;
  std::streamoff bytes = 0;
  const std::string ioError = fiberpli::writeFileAtomically(path,
    [&](std::ostream& out) -> std::string
    {
      status = fiberpli::writeSubstratePly(
        out, in.model, &inner, cell, options, counts, fiberpli::MakeProgress(this));
      if (status.aborted)
      {
        return "aborted";
      }
      if (!status.error.empty())
      {
        return path + ": " + status.error;
      }
      return {};
    });
  if (status.aborted)
  {
    return; // the abort is no error; the old file, if any, is kept
  }
  if (!ioError.empty())
  {
    this->Fail(vtkErrorCode::CannotOpenFileError, fiberpli::ProxyMessage(this, ioError));
    return;
  }
  struct stat info;
  if (::stat(path.c_str(), &info) == 0)
  {
    bytes = static_cast<std::streamoff>(info.st_size);
  }
  this->VerticesWritten = static_cast<double>(counts.vertices);
  this->TrianglesWritten = static_cast<double>(counts.triangles);
  this->BytesWritten = static_cast<double>(bytes);
  vtkLogF(INFO,
    "FiberMeshWriter: %s: %llu surfaces, %llu vertices, %llu triangles, %lld bytes (%d sides)",
    path.c_str(), static_cast<unsigned long long>(counts.surfaces),
    static_cast<unsigned long long>(counts.vertices),
    static_cast<unsigned long long>(counts.triangles), static_cast<long long>(bytes),
    options.sides);

  if (kind != CYLINDERS_NONE)
  {
    const std::string listPath = Stem(path) + ".cylinders.txt";
    const std::string listError = fiberpli::writeFileAtomically(listPath,
      [&](std::ostream& out) -> std::string
      {
        out << cylinders;
        return out ? std::string() : listPath + ": write failed";
      });
    if (!listError.empty())
    {
      this->Fail(vtkErrorCode::CannotOpenFileError,
        fiberpli::ProxyMessage(
          this, path + " was written, its cylinder list was not: " + listError));
      return;
    }
  }
  if (this->WriteMCDCConfig)
  {
    fiberpli::Vec3 lo = cell.lo;
    fiberpli::Vec3 hi = cell.hi;
    if (!cell.enabled() && !fiberpli::modelBounds(in.model, true, lo, hi))
    {
      lo = hi = fiberpli::Vec3{};
    }
    const std::size_t slash = path.find_last_of('/');
    const std::string confPath = Stem(path) + ".mcdc.conf";
    const std::string plyName = slash == std::string::npos ? path : path.substr(slash + 1);
    const std::string confError = fiberpli::writeFileAtomically(confPath,
      [&](std::ostream& out) -> std::string
      {
        out << fiberpli::mcdcConfigSnippet(plyName, lo, hi);
        return out ? std::string() : confPath + ": write failed";
      });
    if (!confError.empty())
    {
      this->Fail(vtkErrorCode::CannotOpenFileError,
        fiberpli::ProxyMessage(
          this, path + " was written, its MC/DC configuration was not: " + confError));
    }
  }
}

//------------------------------------------------------------------------------
void vtkFiberMeshWriter::Fail(unsigned long code, const std::string& message)
{
  vtkErrorMacro(<< message);
  this->SetErrorCode(code);
}

//------------------------------------------------------------------------------
void vtkFiberMeshWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "NumberOfSides: " << this->NumberOfSides << "\n";
  os << indent << "Tolerance: " << this->Tolerance << "\n";
  os << indent << "RingSpacing: " << this->RingSpacing << "\n";
  os << indent << "InnerSurfaces: " << this->InnerSurfaces << "\n";
  os << indent << "WriteMCDCConfig: " << this->WriteMCDCConfig << "\n";
  os << indent << "CylinderList: " << this->CylinderList << "\n";
  os << indent << "StraightnessTolerance: " << this->StraightnessTolerance << "\n";
}
