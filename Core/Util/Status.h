/// Status: the one way a Core operation says how it ended (docs/architecture.md §2). An operation
/// that can fail or be stopped returns a Status, or a result struct that derives from it:
/// - `error` non-empty: it failed; the message names the option, fiber or file and the value, and
///   the outputs are unusable (usually empty);
/// - `aborted`: the progress callback (Util/Progress.h) returned false; the outputs are incomplete
///   and must not be passed on. An abort is no error: `error` stays empty;
/// - `warnings`: it succeeded with recoverable oddities, one message per kind, for the caller to
///   show once.
/// An operation that can neither be stopped nor warn (the checks validate…/check…, a few plain
/// computations) returns just the message that becomes `error` ("" = fine; a Status converts from
/// it).
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace fiberpli
{

struct Status
{
  std::string error;
  bool aborted = false;
  std::vector<std::string> warnings;

  Status() = default;
  /// The outcome of a check: its message ("" = fine) becomes the error.
  Status(std::string message) // NOLINT(google-explicit-constructor): a check's message is a Status
    : error(std::move(message))
  {
  }
  Status(const char* message)
    : error(message)
  {
  }
  /// `return nullptr;` / `return 0;` would build a std::string from a null pointer (undefined).
  Status(std::nullptr_t) = delete;

  /// Neither failed nor stopped.
  bool ok() const { return error.empty() && !aborted; }

  static Status stopped()
  {
    Status s;
    s.aborted = true;
    return s;
  }
};

} // namespace fiberpli
