// Substitution of subexpressions (usually symbols) by expressions, rebuilt in canonical form.
#pragma once

#include <unordered_map>

#include "sym/expr.hpp"

namespace dyncc::sym {

using Substitution = std::unordered_map<Expr, Expr>;

/// Replaces every occurrence of a key by its value (keys matched by identity, i.e. structurally),
/// memoised over the DAG. Values are not substituted again.
Expr substitute(Expr e, const Substitution& map);

/// Rebuilds a node of e's kind from new arguments through the canonicalising constructors.
Expr rebuild(Expr e, std::span<const Expr> new_args);

}  // namespace dyncc::sym
