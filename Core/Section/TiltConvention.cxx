#include "Section/TiltConvention.h"

#include <sstream>

namespace fiberpli
{

std::string tiltConventionFromCode(int code, TiltConvention& convention)
{
  if (code < 0 || code > 1)
  {
    std::ostringstream m;
    m << "TiltConvention is " << code << ", must be 0 (physical) or 1 (fastPLI)";
    return m.str();
  }
  convention = static_cast<TiltConvention>(code);
  return {};
}

} // namespace fiberpli
