/// BinaryIO: byte-order-explicit decoding/encoding and stream sizing for the binary files FiberPLI
/// reads and writes (.tck, .trk, solver checkpoints). Values are assembled byte by byte, so the
/// result never depends on the host's byte order or alignment. Messages between the ranks of one
/// job stay in the host's order (Util/ByteBuffer.h). Internal helper, not part of the public API.
#pragma once

#include <cstdint>
#include <cstring>
#include <istream>

namespace fiberpli
{
namespace binary
{

inline std::uint16_t load16(const unsigned char* p, bool little)
{
  return little ? static_cast<std::uint16_t>(p[0] | (p[1] << 8))
                : static_cast<std::uint16_t>(p[1] | (p[0] << 8));
}

inline std::uint32_t load32(const unsigned char* p, bool little)
{
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i)
  {
    v |= static_cast<std::uint32_t>(p[little ? i : 3 - i]) << (8 * i);
  }
  return v;
}

inline std::uint64_t load64(const unsigned char* p, bool little)
{
  std::uint64_t v = 0;
  for (int i = 0; i < 8; ++i)
  {
    v |= static_cast<std::uint64_t>(p[little ? i : 7 - i]) << (8 * i);
  }
  return v;
}

inline std::int16_t loadInt16(const unsigned char* p, bool little)
{
  const std::uint16_t u = load16(p, little);
  std::int16_t v;
  std::memcpy(&v, &u, sizeof v);
  return v;
}

inline std::int32_t loadInt32(const unsigned char* p, bool little)
{
  const std::uint32_t u = load32(p, little);
  std::int32_t v;
  std::memcpy(&v, &u, sizeof v);
  return v;
}

inline float loadFloat32(const unsigned char* p, bool little)
{
  const std::uint32_t u = load32(p, little);
  float v;
  std::memcpy(&v, &u, sizeof v);
  return v;
}

inline double loadFloat64(const unsigned char* p, bool little)
{
  const std::uint64_t u = load64(p, little);
  double v;
  std::memcpy(&v, &u, sizeof v);
  return v;
}

inline void storeFloat32LE(unsigned char* p, float value)
{
  std::uint32_t u;
  std::memcpy(&u, &value, sizeof u);
  for (int i = 0; i < 4; ++i)
  {
    p[i] = static_cast<unsigned char>(u >> (8 * i));
  }
}

inline void store64LE(unsigned char* p, std::uint64_t value)
{
  for (int i = 0; i < 8; ++i)
  {
    p[i] = static_cast<unsigned char>(value >> (8 * i));
  }
}

inline void storeFloat64LE(unsigned char* p, double value)
{
  std::uint64_t u;
  std::memcpy(&u, &value, sizeof u);
  store64LE(p, u);
}

/// Bytes from the current position to the end of the stream; the position is kept. False when the
/// stream cannot seek (sizes declared in headers must be checked against the real length before
/// anything is allocated, so an unseekable stream is refused).
inline bool remainingBytes(std::istream& in, std::uint64_t& size)
{
  const std::streampos here = in.tellg();
  if (here == std::streampos(-1))
  {
    return false;
  }
  in.seekg(0, std::ios::end);
  const std::streampos end = in.tellg();
  in.clear();
  in.seekg(here);
  if (end == std::streampos(-1) || end < here || !in)
  {
    return false;
  }
  size = static_cast<std::uint64_t>(end - here);
  return true;
}

} // namespace binary
} // namespace fiberpli
