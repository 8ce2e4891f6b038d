/// Test helper: numbers as raw float32/float64 bytes in either byte order, encoded by hand,
/// independent of the readers' own BinaryIO (memcpy gives the host's order, little endian on every
/// platform we build on). For the MRtrix .tck and .tsf tests.
#pragma once

#include <cstddef>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

namespace fiberpli
{
namespace testing
{

inline std::string encode(const std::vector<double>& values, bool float64, bool bigEndian)
{
  std::string out;
  for (double v : values)
  {
    unsigned char b[8];
    const std::size_t n = float64 ? 8 : 4;
    if (float64)
    {
      std::memcpy(b, &v, 8);
    }
    else
    {
      const float f = static_cast<float>(v);
      std::memcpy(b, &f, 4);
    }
    if (bigEndian)
    {
      for (std::size_t i = 0; i < n / 2; ++i)
      {
        std::swap(b[i], b[n - 1 - i]);
      }
    }
    out.append(reinterpret_cast<const char*>(b), n);
  }
  return out;
}

} // namespace testing
} // namespace fiberpli
