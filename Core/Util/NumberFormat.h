/// NumberFormat: the one way numbers are written into messages. A double is written in the
/// shortest form that reads back to the same value ("0.025", "1e+300", "nan"), never the fixed
/// six decimals of std::to_string (which writes 1e300 with 301 digits and 1e-9 as 0.000000);
/// integers are written as they are.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <string>
#include <type_traits>

namespace fiberpli
{

/// The shortest "%g" text (1 to 17 significant digits) that reads back to exactly v ("1000"
/// rather than "1e+03": of the precisions that read back, the one with the fewest characters).
inline std::string formatNumber(double v)
{
  std::string best;
  char text[32];
  bool exact = false;
  for (int digits = 1; digits <= 17; ++digits)
  {
    std::snprintf(text, sizeof text, "%.*g", digits, v);
    exact = exact || std::strtod(text, nullptr) == v; // NaN never does: it ends as "nan"
    if ((exact || digits == 17) && (best.empty() || std::string(text).size() < best.size()))
    {
      best = text;
    }
  }
  return best;
}

inline std::string formatNumber(float v)
{
  return formatNumber(static_cast<double>(v));
}

inline std::string formatNumber(long double v)
{
  return formatNumber(static_cast<double>(v));
}

/// Integers (and bool, char) as std::to_string writes them.
template <typename T, typename std::enable_if<std::is_integral<T>::value, int>::type = 0>
std::string formatNumber(T v)
{
  return std::to_string(v);
}

} // namespace fiberpli
