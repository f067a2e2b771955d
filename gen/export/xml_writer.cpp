#include "export/xml_writer.hpp"

#include <fmt/core.h>

#include <cassert>

namespace dyncc::exporting {
namespace {

std::string escaped(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (const char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

// Built with append throughout: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string at -O3.
std::string start_tag(std::string_view tag, const XmlAttributes& attributes) {
  std::string s = "<";
  s.append(tag);
  for (const auto& [name, value] : attributes)
    s.append(" ").append(name).append("=\"").append(escaped(value)).append("\"");
  return s;
}

}  // namespace

void XmlWriter::indent() { text_.append(2 * open_.size(), ' '); }

void XmlWriter::open(std::string_view tag, const XmlAttributes& attributes) {
  indent();
  text_.append(start_tag(tag, attributes)).append(">\n");
  open_.emplace_back(tag);
}

void XmlWriter::element(std::string_view tag, const XmlAttributes& attributes) {
  indent();
  text_.append(start_tag(tag, attributes)).append("/>\n");
}

void XmlWriter::close() {
  assert(!open_.empty());
  const std::string tag = open_.back();
  open_.pop_back();
  indent();
  text_.append("</").append(tag).append(">\n");
}

void XmlWriter::comment(std::string_view text) {
  std::string safe;
  safe.reserve(text.size());
  for (const char c : text) {
    if (c == '-' && !safe.empty() && safe.back() == '-') safe.push_back(' ');
    safe.push_back(c);
  }
  indent();
  text_.append("<!-- ").append(safe).append(" -->\n");
}

std::string number(double x) { return fmt::format("{}", x == 0.0 ? 0.0 : x); }

std::string numbers(std::initializer_list<double> values) {
  std::string s;
  for (const double v : values) s.append(s.empty() ? "" : " ").append(number(v));
  return s;
}

std::string numbers(const Eigen::Vector3d& v) { return numbers({v.x(), v.y(), v.z()}); }

}  // namespace dyncc::exporting
