#include "IO/TrkFormat.h"
#include "Util/PrintableText.h"

#include "Util/BinaryIO.h"
#include "Util/ValueCheck.h"

#include <cctype>
#include <cmath>
#include <cstring>
#include <sstream>
#include <vector>

namespace fiberpli
{

namespace
{

constexpr std::size_t headerSize = 1000;

std::string at(const std::string& fileName, std::uint64_t byte, const std::string& what)
{
  std::ostringstream msg;
  msg << fileName << " byte " << byte << ": " << what;
  return msg.str();
}

/// Axis (0 = x/R-L, 1 = y/A-P, 2 = z/S-I) and sign (+1 towards R, A, S) of an orientation letter.
bool axisCode(char c, int& axis, int& sign)
{
  switch (c)
  {
    case 'R':
      axis = 0;
      sign = 1;
      return true;
    case 'L':
      axis = 0;
      sign = -1;
      return true;
    case 'A':
      axis = 1;
      sign = 1;
      return true;
    case 'P':
      axis = 1;
      sign = -1;
      return true;
    case 'S':
      axis = 2;
      sign = 1;
      return true;
    case 'I':
      axis = 2;
      sign = -1;
      return true;
    default:
      return false;
  }
}

} // namespace

FiberReadResult readTrk(std::istream& in, const std::string& fileName, double defaultRadius)
{
  FiberReadResult result;
  const auto fail = readFailure;
  if (const std::string bad = defaultRadiusError(fileName, defaultRadius); !bad.empty())
  {
    return fail(bad);
  }
  std::uint64_t fileSize = 0;
  if (!binary::remainingBytes(in, fileSize))
  {
    return fail(fileName + ": cannot determine the file size (stream is not seekable)");
  }
  if (fileSize < headerSize)
  {
    return fail(
      at(fileName, fileSize, "file ends inside the 1000-byte TrackVis header (truncated file?)"));
  }
  unsigned char h[headerSize];
  in.read(reinterpret_cast<char*>(h), headerSize);
  if (static_cast<std::size_t>(in.gcount()) != headerSize)
  {
    return fail(at(fileName, static_cast<std::uint64_t>(in.gcount()), "read error in the header"));
  }
  if (std::memcmp(h, "TRACK", 5) != 0)
  {
    return fail(at(fileName, 0, "not a TrackVis file (magic 'TRACK' missing)"));
  }
  bool little = true;
  if (binary::loadInt32(h + 996, true) == 1000)
  {
    little = true;
  }
  else if (binary::loadInt32(h + 996, false) == 1000)
  {
    little = false;
  }
  else
  {
    return fail(at(fileName, 996, mustBe("hdr_size", binary::loadInt32(h + 996, true), "1000")));
  }
  const std::int32_t version = binary::loadInt32(h + 992, little);
  if (version != 1 && version != 2)
  {
    return fail(
      at(fileName, 992, "version " + std::to_string(version) + " is not supported (1 or 2)"));
  }
  int dim[3];
  double voxelSize[3];
  for (int a = 0; a < 3; ++a)
  {
    dim[a] = binary::loadInt16(h + 6 + 2 * a, little);
    voxelSize[a] = binary::loadFloat32(h + 12 + 4 * a, little);
    if (!std::isfinite(voxelSize[a]) || voxelSize[a] <= 0.0)
    {
      std::ostringstream msg;
      msg << "voxel_size[" << a << "] is " << voxelSize[a] << ", must be finite and > 0";
      return fail(at(fileName, 12 + 4 * static_cast<std::uint64_t>(a), msg.str()));
    }
  }
  const int nScalars = binary::loadInt16(h + 36, little);
  const int nProperties = binary::loadInt16(h + 238, little);
  if (nScalars < 0)
  {
    return fail(at(fileName, 36, "n_scalars " + std::to_string(nScalars) + " is negative"));
  }
  if (nProperties < 0)
  {
    return fail(at(fileName, 238, "n_properties " + std::to_string(nProperties) + " is negative"));
  }
  double A[4][4];
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      A[r][c] = binary::loadFloat32(h + 440 + 4 * (4 * r + c), little);
      if (!std::isfinite(A[r][c]))
      {
        return fail(at(fileName, 440 + 4 * static_cast<std::uint64_t>(4 * r + c),
          "vox_to_ras holds a non-finite value"));
      }
    }
  }

  // Voxel-axis permutation/flip (nibabel: ornt_transform(header voxel_order -> affine axcodes)).
  int sourceAxis[3] = { 0, 1, 2 }; // affine voxel axis k takes header voxel axis sourceAxis[k]
  bool flip[3] = { false, false, false };
  if (A[3][3] == 0.0)
  {
    for (int r = 0; r < 4; ++r)
    {
      for (int c = 0; c < 4; ++c)
      {
        A[r][c] = (r == c) ? (r < 3 ? voxelSize[r] : 1.0) : 0.0;
      }
    }
  }
  else
  {
    char order[3] = { 'L', 'P', 'S' };
    if (h[948] != 0)
    {
      std::memcpy(order, h + 948, 3);
    }
    int headerAxis[3];
    int headerSign[3];
    bool valid = true;
    for (int j = 0; j < 3; ++j)
    {
      valid = valid &&
        axisCode(static_cast<char>(std::toupper(static_cast<unsigned char>(order[j]))),
          headerAxis[j], headerSign[j]);
    }
    if (!valid || headerAxis[0] == headerAxis[1] || headerAxis[1] == headerAxis[2] ||
      headerAxis[0] == headerAxis[2])
    {
      return fail(at(fileName, 948,
        "voxel_order '" + printableText(std::string_view(order, 3)) +
          "' is not three distinct letters of R/L, A/P, S/I"));
    }
    // World axis and direction of each affine voxel axis: the dominant entry of its column.
    int affineAxis[3];
    int affineSign[3];
    for (int k = 0; k < 3; ++k)
    {
      int best = 0;
      for (int r = 1; r < 3; ++r)
      {
        if (std::fabs(A[r][k]) > std::fabs(A[best][k]))
        {
          best = r;
        }
      }
      if (A[best][k] == 0.0)
      {
        return fail(at(fileName, 440,
          "vox_to_ras has an all-zero voxel axis (column " + std::to_string(k) + ")"));
      }
      affineAxis[k] = best;
      affineSign[k] = A[best][k] > 0.0 ? 1 : -1;
    }
    if (affineAxis[0] == affineAxis[1] || affineAxis[1] == affineAxis[2] ||
      affineAxis[0] == affineAxis[2])
    {
      return fail(
        at(fileName, 440, "vox_to_ras does not map the voxel axes to distinct world axes"));
    }
    for (int k = 0; k < 3; ++k)
    {
      for (int j = 0; j < 3; ++j)
      {
        if (headerAxis[j] == affineAxis[k])
        {
          sourceAxis[k] = j;
          flip[k] = headerSign[j] != affineSign[k];
        }
      }
      if (flip[k] && dim[sourceAxis[k]] <= 0)
      {
        return fail(at(fileName, 6 + 2 * static_cast<std::uint64_t>(sourceAxis[k]),
          "dim must be > 0 to flip voxel axis " + std::to_string(sourceAxis[k]) +
            " (voxel_order differs from vox_to_ras)"));
      }
    }
  }

  std::int32_t nCount = binary::loadInt32(h + 988, little);
  if (nCount < 0)
  {
    return fail(at(fileName, 988, "n_count " + std::to_string(nCount) + " is negative"));
  }
  const std::uint64_t bodyBytes = fileSize - headerSize;
  if (static_cast<std::uint64_t>(nCount) > bodyBytes / 4) // a track needs at least its point count
  {
    std::ostringstream msg;
    msg << "n_count " << nCount << " tracks cannot fit in the " << bodyBytes
        << " bytes after the header";
    return fail(at(fileName, 988, msg.str()));
  }
  result.model.fibers.reserve(static_cast<std::size_t>(nCount));

  const std::uint64_t valuesPerPoint = 3 + static_cast<std::uint64_t>(nScalars);
  std::uint64_t position = headerSize;
  std::int64_t track = 0;
  std::vector<unsigned char> buffer;
  while (position < fileSize && (nCount == 0 || track < nCount))
  {
    if (fileSize - position < 4)
    {
      return fail(at(
        fileName, position, "file ends inside the point count of track " + std::to_string(track)));
    }
    unsigned char nb[4];
    in.read(reinterpret_cast<char*>(nb), 4);
    if (in.gcount() != 4)
    {
      return fail(at(fileName, position, "read error"));
    }
    const std::int32_t n = binary::loadInt32(nb, little);
    if (n < 0)
    {
      return fail(at(fileName, position,
        "track " + std::to_string(track) + " has a negative point count " + std::to_string(n)));
    }
    position += 4;
    const std::uint64_t trackBytes = 4 *
      (static_cast<std::uint64_t>(n) * valuesPerPoint + static_cast<std::uint64_t>(nProperties));
    if (trackBytes > fileSize - position)
    {
      std::ostringstream msg;
      msg << "track " << track << " declares " << n << " points (" << trackBytes
          << " bytes) but only " << (fileSize - position) << " bytes remain";
      return fail(at(fileName, position - 4, msg.str()));
    }
    buffer.resize(static_cast<std::size_t>(trackBytes));
    in.read(reinterpret_cast<char*>(buffer.data()), static_cast<std::streamsize>(trackBytes));
    if (static_cast<std::uint64_t>(in.gcount()) != trackBytes)
    {
      return fail(at(fileName, position, "read error"));
    }
    Fiber fiber;
    fiber.points.reserve(static_cast<std::size_t>(n));
    for (std::int32_t i = 0; i < n; ++i)
    {
      const std::uint64_t pointOffset = 4 * valuesPerPoint * static_cast<std::uint64_t>(i);
      double v[3];
      for (int a = 0; a < 3; ++a)
      {
        const double p = binary::loadFloat32(buffer.data() + pointOffset + 4 * a, little);
        if (!std::isfinite(p))
        {
          return fail(at(fileName, position + pointOffset + 4 * a,
            "track " + std::to_string(track) + " point " + std::to_string(i) +
              " has a non-finite coordinate"));
        }
        v[a] = p / voxelSize[a] - 0.5;
      }
      double w[3];
      for (int k = 0; k < 3; ++k)
      {
        w[k] = flip[k] ? (dim[sourceAxis[k]] - 1.0 - v[sourceAxis[k]]) : v[sourceAxis[k]];
      }
      Vec3 world;
      for (int r = 0; r < 3; ++r)
      {
        world[r] = A[r][0] * w[0] + A[r][1] * w[1] + A[r][2] * w[2] + A[r][3];
      }
      fiber.points.push_back(world);
    }
    position += trackBytes;
    if (fiber.points.size() >= 2)
    {
      fiber.id = track;
      fiber.bundle = 0;
      fiber.radii.assign(fiber.points.size(), defaultRadius);
      result.model.fibers.push_back(std::move(fiber));
    }
    else
    {
      ++result.droppedFibers;
    }
    ++track;
  }
  if (nCount > 0 && track < nCount)
  {
    std::ostringstream msg;
    msg << "header n_count " << nCount << " but the file ends after " << track << " tracks";
    return fail(at(fileName, position, msg.str()));
  }
  if (position < fileSize)
  {
    std::ostringstream msg;
    msg << "header n_count " << nCount << " but " << (fileSize - position)
        << " more bytes follow track " << (track - 1);
    return fail(at(fileName, position, msg.str()));
  }
  return result;
}

bool looksLikeTrk(std::istream& in)
{
  const std::streampos start = in.tellg();
  if (start == std::streampos(-1))
  {
    return false;
  }
  unsigned char h[headerSize];
  in.read(reinterpret_cast<char*>(h), headerSize);
  const bool complete = in.gcount() == static_cast<std::streamsize>(headerSize);
  in.clear();
  in.seekg(start);
  return complete && std::memcmp(h, "TRACK", 5) == 0 &&
    (binary::loadInt32(h + 996, true) == 1000 || binary::loadInt32(h + 996, false) == 1000);
}

} // namespace fiberpli
