// Internal to the loader: typed, located access to YAML nodes with diagnostics.
//
// Every accessor reports what was expected at the node's position and returns an empty
// optional instead of throwing, so bad input never escapes as an exception.
#pragma once

#include <yaml-cpp/yaml.h>

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "robot/diagnostics.hpp"
#include "sym/rational.hpp"

namespace dyncc::robot::detail {

/// A node with the field path that leads to it ("links[2].com[0]") and its position.
struct Located {
  YAML::Node node;
  std::string path;
  SourceLocation location;  // of the value; of the key when the value is empty
};

/// Where a scalar's characters are in the file, for pointing inside expressions.
struct ScalarPosition {
  SourceLocation start;  // first character of the content (after an opening quote)
  bool exact = false;    // content maps 1:1 onto the source line (no escapes, no folding)
};

/// Most entries one list or map may have. Far above any real robot; it keeps the name checks
/// (some quadratic in the number of names) fast on a hostile multi-megabyte file.
inline constexpr std::size_t kMaxCollectionSize = 2000;

class YamlReader {
 public:
  YamlReader(std::string_view text, DiagnosticSink& sink) : text_(text), sink_(sink) {}

  [[nodiscard]] DiagnosticSink& sink() { return sink_; }
  [[nodiscard]] SourceLocation location_of(const YAML::Node& node) const;
  [[nodiscard]] ScalarPosition scalar_position(const Located& scalar) const;
  /// Reports a list or map with more than kMaxCollectionSize entries; true when within the limit.
  bool check_size(const Located& collection);

  Located root(const YAML::Node& node) const { return Located{node, "", location_of(node)}; }

  bool expect_map(const Located& value, std::string_view what);
  bool expect_sequence(const Located& value, std::string_view what);
  bool expect_scalar(const Located& value, std::string_view what);

  /// The fields of a map with a fixed schema. Reports unknown keys (with a suggestion from
  /// `known`), duplicate keys and non-scalar keys; returns the valid fields by key.
  std::map<std::string, Located> fields(const Located& map, const std::vector<std::string>& known);

  /// Reports a missing required field at the map's position; returns whether it is there.
  bool require(const std::map<std::string, Located>& fields, const Located& map, const std::string& key,
               std::string_view why = {});

  /// The entries of a map keyed by user-chosen names (constants, parameters), in file order.
  /// Duplicate keys are reported (first one wins) and keys must be scalars.
  std::vector<std::pair<Located, Located>> entries(const Located& map);

  /// The elements of a sequence, with paths "path[i]".
  std::vector<Located> elements(const Located& sequence);

  /// A sequence of exactly `size` elements (gravity, com, points).
  std::optional<std::vector<Located>> fixed_sequence(const Located& value, std::size_t size, std::string_view what);

  /// A finite number (NaN and infinities are rejected with their own message).
  std::optional<double> finite_number(const Located& value);
  /// A number kept exactly ("0.180" is 9/50); rejects values that do not fit exactly.
  std::optional<sym::Rational> exact_number(const Located& value);
  /// Any scalar's text.
  std::optional<std::string> text(const Located& value, std::string_view what);
  /// A name usable as a symbol: [A-Za-z_][A-Za-z0-9_]*, not a reserved word.
  std::optional<std::string> identifier(const Located& value, std::string_view what);

 private:
  std::string_view text_;
  DiagnosticSink& sink_;
};

/// Path helpers: join("links[2]", "theta") == "links[2].theta"; join("", "name") == "name".
std::string join_path(std::string_view parent, std::string_view key);
std::string index_path(std::string_view parent, std::size_t index);

/// Syntax of numbers and names, shared by the reader and the expression checks.
bool looks_like_number(std::string_view text);
bool is_non_finite_spelling(std::string_view text);
bool is_identifier(std::string_view text);
bool is_reserved_word(std::string_view text);
std::string_view node_kind_name(const YAML::Node& node);

}  // namespace dyncc::robot::detail
