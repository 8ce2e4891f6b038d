/// MrtrixData: the binary body shared by MRtrix tracks (.tck, 3 values per point) and track scalars
/// (.tsf, 1 value per point) (docs/api.md §4; MRtrix3 docs, "Tracks file format"):
/// points as groups of values, an all-NaN group after each streamline, an all-Inf group at the end.
/// Internal helper, not part of the public API.
#pragma once

#include "IO/MrtrixHeader.h"
#include "Util/BinaryIO.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <istream>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

namespace fiberpli
{

/// Reads the data section described by header (readMrtrixHeader) in blocks of whole groups of
/// width values. Calls onPoint(const double* values, std::uint64_t byteOffset) for each finite
/// group and onStreamlineEnd() for each NaN group, and for an Inf group that closes a streamline
/// without its NaN (tolerated, MRtrix writes the NaN). Returns "" or an error naming fileName and
/// the byte offset: a group mixing finite and NaN/Inf values, no Inf end marker (truncated), or a
/// header `count` that differs from the number of streamlines. streamlines receives that number.
template <class OnPoint, class OnStreamlineEnd>
std::string walkMrtrixData(std::istream& in, const std::string& fileName,
  const MrtrixHeader& header, std::size_t width, std::uint64_t& streamlines, OnPoint onPoint,
  OnStreamlineEnd onStreamlineEnd)
{
  const char* group = width == 3 ? "triplet" : "value";
  const std::uint64_t groupSize = width * header.valueSize;
  in.clear();
  in.seekg(static_cast<std::streamoff>(header.dataOffset));
  if (!in)
  {
    return mrtrixErrorAt(fileName, "byte", header.dataOffset, "cannot seek to the data");
  }
  const std::size_t groupsPerBlock = 1 << 12;
  std::vector<unsigned char> block(static_cast<std::size_t>(groupSize) * groupsPerBlock);
  std::uint64_t remaining = header.fileSize - header.dataOffset;
  std::uint64_t position = header.dataOffset;
  std::uint64_t pointsInStreamline = 0;
  bool sawEnd = false;
  streamlines = 0;
  double v[3];
  while (!sawEnd && remaining >= groupSize)
  {
    const std::size_t groups =
      static_cast<std::size_t>(std::min<std::uint64_t>(remaining / groupSize, groupsPerBlock));
    const std::size_t bytes = groups * static_cast<std::size_t>(groupSize);
    in.read(reinterpret_cast<char*>(block.data()), static_cast<std::streamsize>(bytes));
    if (static_cast<std::size_t>(in.gcount()) != bytes)
    {
      return mrtrixErrorAt(
        fileName, "byte", position + static_cast<std::uint64_t>(in.gcount()), "read error");
    }
    for (std::size_t g = 0; g < groups; ++g, position += groupSize)
    {
      const unsigned char* p = block.data() + g * groupSize;
      std::size_t nans = 0;
      std::size_t infs = 0;
      for (std::size_t a = 0; a < width; ++a)
      {
        v[a] = header.valueSize == 4
          ? static_cast<double>(binary::loadFloat32(p + a * 4, header.littleEndian))
          : binary::loadFloat64(p + a * 8, header.littleEndian);
        nans += std::isnan(v[a]) ? 1 : 0;
        infs += std::isinf(v[a]) ? 1 : 0;
      }
      if (nans == 0 && infs == 0)
      {
        onPoint(static_cast<const double*>(v), position);
        ++pointsInStreamline;
        continue;
      }
      if (nans == width)
      {
        onStreamlineEnd();
        ++streamlines;
        pointsInStreamline = 0;
        continue;
      }
      if (infs == width)
      {
        if (pointsInStreamline > 0)
        {
          onStreamlineEnd();
          ++streamlines;
        }
        sawEnd = true;
        break;
      }
      return mrtrixErrorAt(
        fileName, "byte", position, std::string(group) + " mixes finite and NaN/Inf values");
    }
    remaining -= bytes;
  }
  if (!sawEnd)
  {
    return mrtrixErrorAt(fileName, "byte", header.fileSize,
      std::string("data ends without the Inf end-of-tracks ") + group + " (truncated file?)");
  }
  if (header.haveCount && streamlines != header.count)
  {
    std::ostringstream msg;
    msg << "header count " << header.count << " but the data holds " << streamlines
        << " streamlines";
    return mrtrixErrorAt(fileName, "line", header.countLine, msg.str());
  }
  return {};
}

/// Buffered little-endian float32 output for the MRtrix writers (one write per 48 KiB).
class MrtrixFloat32Writer
{
public:
  explicit MrtrixFloat32Writer(std::ostream& out)
    : out_(out)
    , block_(4 * 12 * 1024)
  {
  }

  void put(float value)
  {
    if (used_ == block_.size())
    {
      flush();
    }
    binary::storeFloat32LE(block_.data() + used_, value);
    used_ += 4;
  }

  /// Writes what is buffered; call once at the end.
  void flush()
  {
    out_.write(reinterpret_cast<const char*>(block_.data()), static_cast<std::streamsize>(used_));
    used_ = 0;
  }

private:
  std::ostream& out_;
  std::vector<unsigned char> block_;
  std::size_t used_ = 0;
};

} // namespace fiberpli
