// Text for the HTML pages that show the figures (dyncc report, dyncc diagnose --out).
#pragma once

#include <string>

namespace dyncc::plot {

/// `text` with the characters HTML gives a meaning (< > & ") written as entities.
inline std::string html_escape(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else if (c == '"')
      out += "&quot;";
    else
      out += c;
  }
  return out;
}

}  // namespace dyncc::plot
