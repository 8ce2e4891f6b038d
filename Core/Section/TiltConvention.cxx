#include "Section/TiltConvention.h"

#include "Util/EnumCode.h"

namespace fiberpli
{

std::string tiltConventionFromCode(int code, TiltConvention& convention)
{
  return enumFromCode(code, 1, "TiltConvention", "0 (physical) or 1 (fastPLI)", convention);
}

} // namespace fiberpli
