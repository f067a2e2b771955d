// A small XML writer for the two export formats: nested elements with attributes, comments,
// two-space indentation, and numbers that read back as the same double.
#pragma once

#include <Eigen/Dense>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace dyncc::exporting {

using XmlAttributes = std::vector<std::pair<std::string, std::string>>;

class XmlWriter {
 public:
  /// <tag a="1" ...>, closed later by close().
  void open(std::string_view tag, const XmlAttributes& attributes = {});
  /// <tag a="1" .../>
  void element(std::string_view tag, const XmlAttributes& attributes = {});
  void close();
  /// <!-- text -->; "--", which XML forbids inside comments, becomes "- -".
  void comment(std::string_view text);
  void blank_line() { text_ += '\n'; }

  /// The document; every opened element must have been closed.
  [[nodiscard]] const std::string& text() const { return text_; }

 private:
  void indent();
  std::string text_;
  std::vector<std::string> open_;
};

/// The shortest decimal text that reads back as x ("0" for -0).
std::string number(double x);
/// Numbers separated by single spaces.
std::string numbers(std::initializer_list<double> values);
std::string numbers(const Eigen::Vector3d& v);

}  // namespace dyncc::exporting
