/// FiberReadResult: what every fiber reader of Core/IO returns (docs/api.md §4).
/// Readers never throw and never print: a failure is the Status error (Util/Status.h), a message
/// that names the file and the line (text formats) or byte offset (binary formats); on failure the
/// model is empty.
#pragma once

#include "Model/FiberModel.h"
#include "Util/Status.h"
#include "Util/ValueCheck.h"

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

namespace fiberpli
{

/// error: empty when the file was read; else "<file> line N: ..." or "<file> byte N: ...".
struct FiberReadResult : Status
{
  FiberModel model;
  /// Fibers/streamlines of fewer than 2 points in the file. They are not in the model (the data
  /// contract needs >= 2 points) but keep their place in the fiber id numbering; the VTK side
  /// reports the count as one warning.
  std::size_t droppedFibers = 0;
  /// The box size of formats that hold one (line 1 of a CACTUS strand list, µm; CACTUS writes -1
  /// when it has none, and -1 here means the same). Axon radii inside the outer ones (CATERPillar)
  /// travel with the fibers, in Fiber::innerRadii, as for every other format.
  double boxSize = -1.0;
};

/// A failed read: empty model, the given message.
inline FiberReadResult readFailure(const std::string& message)
{
  FiberReadResult failed;
  failed.error = message;
  return failed;
}

/// "" when defaultRadius can stand for the radius of files without radii, else the message.
inline std::string defaultRadiusError(const std::string& fileName, double defaultRadius)
{
  if (std::isfinite(defaultRadius) && defaultRadius > 0.0)
  {
    return {};
  }
  return fileName + ": " + valueMustBe("DefaultRadius", defaultRadius, "finite and > 0");
}

} // namespace fiberpli
