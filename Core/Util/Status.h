/// Status: the one way a Core operation says how it ended (docs/architecture.md §2). An operation
/// that can fail or be stopped returns a Status, or a result struct that derives from it:
/// - `error` non-empty: it failed; the message names the option, fiber or file and the value, and
///   the outputs are unusable (usually empty);
/// - `aborted`: the progress callback (Util/Progress.h) returned false; the outputs are incomplete
///   and must not be passed on. An abort is no error: `error` stays empty;
/// - `warnings`: it succeeded with recoverable oddities, one message per kind, for the caller to
///   show once.
/// A pure check that can neither be stopped nor warn (validate…/check…) returns just the message
/// that becomes `error` ("" = fine).
#pragma once

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

  /// Neither failed nor stopped.
  bool ok() const { return error.empty() && !aborted; }

  static Status failure(std::string message)
  {
    Status s;
    s.error = std::move(message);
    return s;
  }
  static Status stopped()
  {
    Status s;
    s.aborted = true;
    return s;
  }
};

} // namespace fiberpli
