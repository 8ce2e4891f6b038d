/// TextFields: the token and number parsing the whitespace-separated list formats of Core/IO share
/// (CATERPillar, CACTUS). Internal helper, not part of the public API.
#pragma once

#include <charconv>
#include <cmath>
#include <cstddef>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>

namespace fiberpli
{
namespace textfields
{

inline bool isBlankChar(char c)
{
  return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}

/// Splits line into at most maxTokens tokens; returns the number of tokens the line holds (which
/// may exceed maxTokens: the extra ones are counted, not stored).
inline std::size_t splitTokens(
  std::string_view line, std::string_view* tokens, std::size_t maxTokens)
{
  std::size_t count = 0;
  std::size_t i = 0;
  const std::size_t n = line.size();
  while (i < n)
  {
    while (i < n && isBlankChar(line[i]))
    {
      ++i;
    }
    if (i == n)
    {
      break;
    }
    std::size_t e = i;
    while (e < n && !isBlankChar(line[e]))
    {
      ++e;
    }
    if (count < maxTokens)
    {
      tokens[count] = line.substr(i, e - i);
    }
    ++count;
    i = e;
  }
  return count;
}

/// A finite double from the whole token (a leading '+' accepted, as Python's float() does); ""
/// when fine, else why not (for a message).
inline std::string parseFinite(std::string_view token, double& value)
{
  const char* first = token.data();
  const char* last = token.data() + token.size();
  if (last - first > 1 && *first == '+')
  {
    ++first;
  }
  const std::from_chars_result r = std::from_chars(first, last, value);
  if (r.ec == std::errc::result_out_of_range)
  {
    return "'" + std::string(token.substr(0, 40)) + "' is not a finite number";
  }
  if (r.ec != std::errc() || r.ptr != last)
  {
    return "'" + std::string(token.substr(0, 40)) + "' is not a number";
  }
  if (!std::isfinite(value))
  {
    return "'" + std::string(token.substr(0, 40)) + "' is not a finite number";
  }
  return {};
}

/// A non-negative integer from the whole token; "" when fine, else why not.
inline std::string parseCount(std::string_view token, unsigned long long& value)
{
  const std::from_chars_result r =
    std::from_chars(token.data(), token.data() + token.size(), value);
  if (r.ec == std::errc::result_out_of_range)
  {
    return "count '" + std::string(token.substr(0, 40)) + "' is too large";
  }
  if (r.ec != std::errc() || r.ptr != token.data() + token.size())
  {
    return "'" + std::string(token.substr(0, 40)) + "' is not a non-negative integer count";
  }
  return {};
}

inline std::string lineError(const std::string& fileName, std::size_t line, const std::string& what)
{
  std::ostringstream msg;
  msg << fileName << " line " << line << ": " << what;
  return msg.str();
}

/// Appends the shortest text that reads back as exactly x.
inline void appendNumber(std::string& out, double x)
{
  char buffer[32];
  const std::to_chars_result r = std::to_chars(buffer, buffer + sizeof(buffer), x);
  out.append(buffer, static_cast<std::size_t>(r.ptr - buffer));
}

} // namespace textfields
} // namespace fiberpli
