/// PrintableText: the one way text read from a file goes into a message. A damaged or binary file
/// can hold any bytes, and a message shows up in a terminal, where raw control bytes (escape
/// sequences) would act on it, and in ParaView's Output Messages. So bytes outside printable
/// ASCII are written as \xNN, a backslash as \\, and the text is cut after `maxChars` characters
/// of the original ("..." marks the cut).
#pragma once

#include <cstddef>
#include <cstdio>
#include <string>
#include <string_view>

namespace fiberpli
{

inline std::string printableText(std::string_view text, std::size_t maxChars = 40)
{
  std::string out;
  const std::size_t n = text.size() < maxChars ? text.size() : maxChars;
  for (std::size_t i = 0; i < n; ++i)
  {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c == '\\')
    {
      out += "\\\\";
    }
    else if (c >= 0x20 && c < 0x7f)
    {
      out += static_cast<char>(c);
    }
    else
    {
      char hex[5];
      std::snprintf(hex, sizeof hex, "\\x%02x", c);
      out += hex;
    }
  }
  if (text.size() > maxChars)
  {
    out += "...";
  }
  return out;
}

} // namespace fiberpli
