/// FiberReadResult: what every fiber reader of Core/IO returns (api.md "Readers and writers").
/// Readers never throw and never print: a failure is an error message that names the file and the
/// line (text formats) or byte offset (binary formats); on failure the model is empty.
#pragma once

#include "Model/FiberModel.h"

#include <cstddef>
#include <string>

namespace fiberpli
{

struct FiberReadResult
{
  FiberModel model;
  /// Empty when the file was read; else "<file> line N: ..." or "<file> byte N: ...".
  std::string error;
  /// Fibers/streamlines of fewer than 2 points in the file. They are not in the model (the data
  /// contract needs >= 2 points) but keep their place in the fiber id numbering; the VTK side
  /// reports the count as one warning.
  std::size_t droppedFibers = 0;

  bool ok() const { return error.empty(); }
};

} // namespace fiberpli
