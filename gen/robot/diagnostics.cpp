#include "robot/diagnostics.hpp"

#include <fmt/core.h>

#include <algorithm>

namespace dyncc::robot {

std::string Diagnostic::format() const {
  std::string text = file;
  if (location.known()) text += fmt::format(":{}:{}", location.line, std::max(location.column, 1));
  text += severity == Severity::Error ? ": error: " : ": warning: ";
  if (!field.empty()) text += field + ": ";
  text += message;
  if (!suggestion.empty()) text += fmt::format("; did you mean '{}'?", suggestion);
  return text;
}

std::string unknown_name_message(std::string_view what, std::string_view name, std::string_view expected,
                                 std::string_view suggestion) {
  if (!suggestion.empty()) return fmt::format("unknown {} '{}'", what, name);
  return fmt::format("unknown {} '{}' ({})", what, name, expected);
}

void DiagnosticSink::error(SourceLocation location, std::string field, std::string message, std::string suggestion) {
  add(Severity::Error, location, std::move(field), std::move(message), std::move(suggestion));
}

void DiagnosticSink::warning(SourceLocation location, std::string field, std::string message, std::string suggestion) {
  add(Severity::Warning, location, std::move(field), std::move(message), std::move(suggestion));
}

void DiagnosticSink::add(Severity severity, SourceLocation location, std::string field, std::string message,
                         std::string suggestion) {
  if (severity == Severity::Error) ++error_count_;
  if (diagnostics_.size() >= kMaxDiagnostics) {
    truncated_ = true;
    return;
  }
  diagnostics_.push_back(
      Diagnostic{severity, file_, location, std::move(field), std::move(message), std::move(suggestion)});
}

std::vector<Diagnostic> DiagnosticSink::sorted() const {
  std::vector<Diagnostic> result = diagnostics_;
  std::stable_sort(result.begin(), result.end(), [](const Diagnostic& a, const Diagnostic& b) {
    if (a.location.line != b.location.line) return a.location.line < b.location.line;
    return a.location.column < b.location.column;
  });
  if (truncated_) {
    result.push_back(Diagnostic{
        Severity::Error, file_, {}, {}, fmt::format("too many problems; stopped after {}", kMaxDiagnostics), {}});
  }
  return result;
}

}  // namespace dyncc::robot
