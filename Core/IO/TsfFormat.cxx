#include "IO/TsfFormat.h"

#include "IO/MrtrixData.h"
#include "IO/MrtrixHeader.h"

#include <cmath>
#include <limits>
#include <sstream>

namespace fiberpli
{

TsfReadResult readTsf(std::istream& in, const std::string& fileName)
{
  TsfReadResult result;
  auto fail = [&](const std::string& message)
  {
    TsfReadResult failed;
    failed.error = message;
    return failed;
  };
  const MrtrixHeader header =
    readMrtrixHeader(in, fileName, "mrtrix track scalars", "MRtrix track scalars", 1);
  if (!header.error.empty())
  {
    return fail(header.error);
  }
  result.valueSize = header.valueSize;
  result.timestamp = header.timestamp;
  if (header.haveCount)
  {
    result.values.reserve(static_cast<std::size_t>(header.count)); // bounded by the file size
    result.firstValueOffsets.reserve(static_cast<std::size_t>(header.count));
  }
  std::uint64_t streamlines = 0;
  std::vector<double> current;
  bool started = false;
  std::uint64_t groupStart = header.dataOffset; // where the current streamline begins
  const std::string error = walkMrtrixData(
    in, fileName, header, 1, streamlines,
    [&](const double* v, std::uint64_t at)
    {
      if (!started)
      {
        groupStart = at;
        started = true;
      }
      current.push_back(v[0]);
    },
    [&]()
    {
      current.shrink_to_fit();
      result.values.push_back(std::move(current));
      result.firstValueOffsets.push_back(groupStart);
      current = {};
      // The next streamline starts after this one's values and its NaN.
      groupStart += (result.values.back().size() + 1) * header.valueSize;
      started = false;
    });
  if (!error.empty())
  {
    return fail(error);
  }
  return result;
}

std::string writeTsf(
  std::ostream& out, const std::vector<std::vector<double>>& values, const std::string& timestamp)
{
  if (timestamp.find_first_of("\r\n") != std::string::npos)
  {
    return "cannot write .tsf: the timestamp '" + timestamp + "' contains a line break";
  }
  const double floatMax = static_cast<double>(std::numeric_limits<float>::max());
  for (std::size_t s = 0; s < values.size(); ++s)
  {
    for (std::size_t i = 0; i < values[s].size(); ++i)
    {
      if (!std::isfinite(values[s][i]) || std::fabs(values[s][i]) > floatMax)
      {
        std::ostringstream msg;
        msg << "cannot write .tsf: streamline " << s << " point " << i << " has value "
            << values[s][i] << " (must be finite and within the float32 range)";
        return msg.str();
      }
    }
  }
  std::string keys = "datatype: Float32LE\n";
  if (!timestamp.empty())
  {
    keys += "timestamp: " + timestamp + "\n";
  }
  keys += "count: " + std::to_string(values.size()) + "\n";
  const std::string header = composeMrtrixHeader("mrtrix track scalars", keys);
  out.write(header.data(), static_cast<std::streamsize>(header.size()));
  MrtrixFloat32Writer data(out);
  for (const std::vector<double>& streamline : values)
  {
    for (double v : streamline)
    {
      data.put(static_cast<float>(v));
    }
    data.put(std::numeric_limits<float>::quiet_NaN());
  }
  data.put(std::numeric_limits<float>::infinity());
  data.flush();
  out.flush();
  if (!out)
  {
    return "cannot write .tsf: the output stream failed";
  }
  return {};
}

} // namespace fiberpli
