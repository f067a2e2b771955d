// Diagnostics: what is wrong with a robot description, where, and what was expected.
//
// Printed in the compiler format editors understand:
//   robots/x.yaml:12:7: error: links[2].theta: unknown symbol 'q4'; did you mean 'q3'?
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "robot/description.hpp"

namespace dyncc::robot {

enum class Severity { Error, Warning };

struct Diagnostic {
  Severity severity = Severity::Error;
  std::string file;
  SourceLocation location;  // 1-based; line 0 = the file as a whole
  std::string field;        // e.g. "links[2].inertia.xy"; empty for file-level problems
  std::string message;      // what is wrong and what was expected
  std::string suggestion;   // a name for "did you mean '...'?"; empty when none is close

  [[nodiscard]] bool is_error() const { return severity == Severity::Error; }
  /// "file:line:column: error: field: message; did you mean 'x'?"
  [[nodiscard]] std::string format() const;
};

/// "unknown WHAT 'name'" followed by "; did you mean" when there is a suggestion, otherwise by
/// " (EXPECTED)" so the reader learns what would have been valid.
std::string unknown_name_message(std::string_view what, std::string_view name, std::string_view expected,
                                 std::string_view suggestion);

/// Collects diagnostics for one file. Stops collecting after a cap so a pathological file
/// cannot produce unbounded output, but always records that it stopped.
class DiagnosticSink {
 public:
  explicit DiagnosticSink(std::string file) : file_(std::move(file)) {}

  void error(SourceLocation location, std::string field, std::string message, std::string suggestion = {});
  void warning(SourceLocation location, std::string field, std::string message, std::string suggestion = {});
  void add(Severity severity, SourceLocation location, std::string field, std::string message,
           std::string suggestion = {});

  [[nodiscard]] bool has_errors() const { return error_count_ > 0; }
  /// True once further diagnostics would be dropped: callers skip costly suggestions then.
  [[nodiscard]] bool saturated() const { return diagnostics_.size() >= kMaxDiagnostics; }
  [[nodiscard]] std::size_t error_count() const { return error_count_; }
  [[nodiscard]] const std::string& file() const { return file_; }
  /// All diagnostics, ordered by position in the file (stable for equal positions).
  [[nodiscard]] std::vector<Diagnostic> sorted() const;

  static constexpr std::size_t kMaxDiagnostics = 100;

 private:
  std::string file_;
  std::vector<Diagnostic> diagnostics_;
  std::size_t error_count_ = 0;
  bool truncated_ = false;
};

}  // namespace dyncc::robot
