/// One rule for every enumerated property: its integer code (the ParaView XML value) becomes the
/// Core enum only when it names one of the enum's values; any other code is refused, never cast.
#pragma once

#include <sstream>
#include <string>

namespace fiberpli
{

/// Codes 0..last are the values of Enum in order: "" and `value` set, or "<property> is <code>,
/// must be <choices>" (choices lists the codes and their names, e.g. "0 (Auto) or 1 (Tilt)").
template <typename Enum>
std::string enumFromCode(int code, int last, const char* property, const char* choices, Enum& value)
{
  if (code < 0 || code > last)
  {
    std::ostringstream m;
    m << property << " is " << code << ", must be " << choices;
    return m.str();
  }
  value = static_cast<Enum>(code);
  return {};
}

} // namespace fiberpli
