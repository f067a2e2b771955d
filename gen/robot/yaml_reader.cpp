#include "robot/yaml_reader.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <set>

#include "robot/spelling.hpp"

namespace dyncc::robot::detail {

std::string join_path(std::string_view parent, std::string_view key) {
  if (parent.empty()) return std::string(key);
  return fmt::format("{}.{}", parent, key);
}

std::string index_path(std::string_view parent, std::size_t index) { return fmt::format("{}[{}]", parent, index); }

namespace {

bool is_digit(char c) { return c >= '0' && c <= '9'; }

std::string lowercase(std::string_view text) {
  std::string result(text);
  for (char& c : result) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return result;
}

// Quotes long scalars only partly so a 10 kB value does not flood the terminal.
std::string quoted_excerpt(std::string_view text) {
  constexpr std::size_t kMax = 40;
  if (text.size() <= kMax) return fmt::format("'{}'", text);
  return fmt::format("'{}...'", text.substr(0, kMax));
}

}  // namespace

bool looks_like_number(std::string_view text) {
  std::size_t i = 0;
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
  std::size_t digits = 0;
  while (i < text.size() && is_digit(text[i])) ++i, ++digits;
  if (i < text.size() && text[i] == '.') {
    ++i;
    while (i < text.size() && is_digit(text[i])) ++i, ++digits;
  }
  if (digits == 0) return false;
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
    std::size_t exponent_digits = 0;
    while (i < text.size() && is_digit(text[i])) ++i, ++exponent_digits;
    if (exponent_digits == 0) return false;
  }
  return i == text.size();
}

bool is_non_finite_spelling(std::string_view text) {
  // YAML 1.2 writes .nan/.inf; C and Python users write nan/inf/infinity.
  static const std::set<std::string> spellings = {".nan", "nan", ".inf", "inf", "infinity"};
  std::string_view body = text;
  if (!body.empty() && (body.front() == '+' || body.front() == '-')) body.remove_prefix(1);
  return spellings.contains(lowercase(body));
}

bool is_identifier(std::string_view text) {
  if (text.empty() || text.size() > 100) return false;
  const auto start = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; };
  if (!start(text.front())) return false;
  return std::all_of(text.begin(), text.end(), [&](char c) { return start(c) || is_digit(c); });
}

bool is_reserved_word(std::string_view text) {
  static const std::set<std::string_view> reserved = {"pi", "sin", "cos", "sqrt", "atan2"};
  return reserved.contains(text) || is_non_finite_spelling(text);
}

std::string_view node_kind_name(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Null: return "nothing (an empty value)";
    case YAML::NodeType::Scalar: return "a single value";
    case YAML::NodeType::Sequence: return "a list";
    case YAML::NodeType::Map: return "a map of 'key: value' pairs";
    case YAML::NodeType::Undefined: break;
  }
  return "nothing";
}

SourceLocation YamlReader::location_of(const YAML::Node& node) const {
  if (!node.IsDefined()) return {};
  const YAML::Mark mark = node.Mark();
  if (mark.is_null() || mark.line < 0) return {};
  return SourceLocation{mark.line + 1, mark.column + 1};
}

ScalarPosition YamlReader::scalar_position(const Located& scalar) const {
  ScalarPosition position{scalar.location, false};
  if (!scalar.node.IsDefined() || !scalar.node.IsScalar()) return position;
  const YAML::Mark mark = scalar.node.Mark();
  if (mark.is_null() || mark.pos < 0 || static_cast<std::size_t>(mark.pos) >= text_.size()) return position;
  const auto pos = static_cast<std::size_t>(mark.pos);
  const std::string& content = scalar.node.Scalar();
  std::size_t content_start = pos;
  if (text_[pos] == '"' || text_[pos] == '\'') {
    content_start = pos + 1;
    position.start.column += 1;
  } else if (text_[pos] == '|' || text_[pos] == '>') {
    return position;  // block scalar: the content starts on a later line
  }
  // Exact only when the characters in the file are the scalar's characters, on one line.
  position.exact = content.find('\n') == std::string::npos && text_.substr(content_start, content.size()) == content;
  return position;
}

namespace {
bool expect_kind(YamlReader& reader, const Located& value, YAML::NodeType::value kind, std::string_view expected,
                 std::string_view what) {
  if (value.node.IsDefined() && value.node.Type() == kind) return true;
  reader.sink().error(value.location, value.path,
                      fmt::format("expected {} ({}), got {}", expected, what, node_kind_name(value.node)));
  return false;
}
}  // namespace

bool YamlReader::expect_map(const Located& value, std::string_view what) {
  return expect_kind(*this, value, YAML::NodeType::Map, "a map of 'key: value' pairs", what);
}

bool YamlReader::expect_sequence(const Located& value, std::string_view what) {
  return expect_kind(*this, value, YAML::NodeType::Sequence, "a list", what);
}

bool YamlReader::expect_scalar(const Located& value, std::string_view what) {
  return expect_kind(*this, value, YAML::NodeType::Scalar, "a single value", what);
}

bool YamlReader::check_size(const Located& collection) {
  if (collection.node.size() <= kMaxCollectionSize) return true;
  sink_.error(collection.location, collection.path,
              fmt::format("{} entries; at most {} are accepted", collection.node.size(), kMaxCollectionSize));
  return false;
}

std::vector<std::pair<Located, Located>> YamlReader::entries(const Located& map) {
  std::vector<std::pair<Located, Located>> result;
  if (!map.node.IsMap() || !check_size(map)) return result;
  std::map<std::string, SourceLocation> seen;
  for (auto it = map.node.begin(); it != map.node.end(); ++it) {
    const YAML::Node key = it->first;
    const SourceLocation key_location = location_of(key);
    if (!key.IsScalar()) {
      sink_.error(key_location, map.path, fmt::format("keys must be plain names, got {}", node_kind_name(key)));
      continue;
    }
    const std::string& name = key.Scalar();
    const std::string path = join_path(map.path, name);
    if (const auto earlier = seen.find(name); earlier != seen.end()) {
      sink_.error(key_location, path,
                  fmt::format("duplicate key '{}' (first given at line {}, column {})", name, earlier->second.line,
                              earlier->second.column));
      continue;
    }
    seen.emplace(name, key_location);
    const YAML::Node value = it->second;
    const SourceLocation value_location = value.IsNull() ? key_location : location_of(value);
    result.emplace_back(Located{key, path, key_location}, Located{value, path, value_location});
  }
  return result;
}

std::map<std::string, Located> YamlReader::fields(const Located& map, const std::vector<std::string>& known) {
  std::map<std::string, Located> result;
  for (auto& [key, value] : entries(map)) {
    const std::string& name = key.node.Scalar();
    bool is_known = false;
    for (const std::string& k : known) is_known = is_known || k == name;
    if (!is_known) {
      std::string expected = "expected one of: ";
      for (std::size_t i = 0; i < known.size(); ++i) expected += (i ? ", " : "") + known[i];
      const std::string suggestion = closest_match(name, known);
      sink_.error(key.location, key.path, unknown_name_message("field", name, expected, suggestion), suggestion);
      continue;
    }
    result.emplace(name, std::move(value));
  }
  return result;
}

bool YamlReader::require(const std::map<std::string, Located>& fields, const Located& map, const std::string& key,
                         std::string_view why) {
  if (fields.contains(key)) return true;
  std::string message = fmt::format("missing required field '{}'", key);
  if (!why.empty()) message += fmt::format(" ({})", why);
  sink_.error(map.location, map.path, std::move(message));
  return false;
}

std::vector<Located> YamlReader::elements(const Located& sequence) {
  std::vector<Located> result;
  if (!sequence.node.IsSequence() || !check_size(sequence)) return result;
  std::size_t index = 0;
  for (const YAML::Node& element : sequence.node) {
    const SourceLocation location = element.IsNull() ? sequence.location : location_of(element);
    result.push_back(Located{element, index_path(sequence.path, index), location});
    ++index;
  }
  return result;
}

std::optional<std::vector<Located>> YamlReader::fixed_sequence(const Located& value, std::size_t size,
                                                               std::string_view what) {
  if (!expect_sequence(value, what)) return std::nullopt;
  std::vector<Located> items = elements(value);
  if (items.size() != size) {
    sink_.error(value.location, value.path,
                fmt::format("expected a list of {} values ({}), got {}", size, what, items.size()));
    return std::nullopt;
  }
  return items;
}

std::optional<double> YamlReader::finite_number(const Located& value) {
  if (!expect_scalar(value, "a number")) return std::nullopt;
  const std::string& text = value.node.Scalar();
  if (is_non_finite_spelling(text)) {
    sink_.error(value.location, value.path,
                fmt::format("expected a finite number, got {} (NaN and infinities are not allowed)", text));
    return std::nullopt;
  }
  if (!looks_like_number(text)) {
    sink_.error(value.location, value.path, fmt::format("expected a number, got {}", quoted_excerpt(text)));
    return std::nullopt;
  }
  std::string_view digits = text;
  if (digits.front() == '+') digits.remove_prefix(1);
  double result = 0.0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), result);
  if (error != std::errc() || end != digits.data() + digits.size() || !std::isfinite(result)) {
    sink_.error(value.location, value.path, fmt::format("number {} is out of range", quoted_excerpt(text)));
    return std::nullopt;
  }
  return result;
}

std::optional<sym::Rational> YamlReader::exact_number(const Located& value) {
  if (!finite_number(value)) return std::nullopt;
  std::string_view digits = value.node.Scalar();
  const bool negative = digits.front() == '-';
  if (digits.front() == '+' || digits.front() == '-') digits.remove_prefix(1);
  sym::Rational result;
  if (!sym::Rational::parse_decimal(digits, result)) {
    sink_.error(value.location, value.path,
                fmt::format("number {} cannot be kept exactly (use at most 18 significant digits and an "
                            "exponent between -38 and 38)",
                            quoted_excerpt(value.node.Scalar())));
    return std::nullopt;
  }
  return negative ? -result : result;
}

std::optional<std::string> YamlReader::text(const Located& value, std::string_view what) {
  if (!expect_scalar(value, what)) return std::nullopt;
  return value.node.Scalar();
}

std::optional<std::string> YamlReader::identifier(const Located& value, std::string_view what) {
  if (!expect_scalar(value, what)) return std::nullopt;
  const std::string& name = value.node.Scalar();
  if (!is_identifier(name)) {
    sink_.error(value.location, value.path,
                fmt::format("expected {} (a letter or '_' followed by letters, digits or '_'), got {}", what,
                            quoted_excerpt(name)));
    return std::nullopt;
  }
  if (is_reserved_word(name)) {
    sink_.error(value.location, value.path,
                fmt::format("'{}' is reserved (pi, sin, cos, sqrt, atan2, nan, inf) and cannot be used as {}", name,
                            what));
    return std::nullopt;
  }
  return name;
}

}  // namespace dyncc::robot::detail
