#include "export/export_error.hpp"

#include <utility>

namespace dyncc::exporting {

ExportError error_at(const std::string& file, robot::SourceLocation at, std::string field, std::string message) {
  const robot::Diagnostic d{robot::Severity::Error, file, at, std::move(field), std::move(message), {}};
  return ExportError{d.format()};
}

robot::Diagnostic warning_at(const std::string& file, robot::SourceLocation at, std::string field,
                             std::string message) {
  return {robot::Severity::Warning, file, at, std::move(field), std::move(message), {}};
}

}  // namespace dyncc::exporting
