// The expression DAG: immutable, hash-consed nodes in canonical form.
//
// Every structurally equal expression is one node, so equality is a pointer compare and a
// memo table keyed by node pointer shares work across the whole DAG (the SymEngine/CasADi
// idea). Canonical form is established by the constructors, never by a later pass:
//   Add  = constant + sum_i coef_i * term_i   (flattened, terms sorted, like terms collected,
//                                               no term is a Number or carries a coefficient)
//   Mul  = coef * prod_i base_i ^ exp_i       (flattened, bases sorted, integer exponents merged,
//                                               no base is a Number or a Mul)
//   a number times a sum is distributed:  2*(x + y) -> 2*x + 2*y
//   sin/cos pull out multiples of pi/2 exactly and use odd/even symmetry on the argument.
// Operand order is by a deterministic structural hash (never by address), so output is
// byte-identical from run to run. Nodes live in a process-wide pool and are never freed:
// the generator is a short-lived compiler process. The pool is not thread-safe.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sym/rational.hpp"

namespace dyncc::sym {

enum class Kind : std::uint8_t { Number, Constant, Symbol, Add, Mul, Sin, Cos, Sqrt, Atan2 };

struct Node;

/// A handle to an interned node. Cheap to copy; compares by identity (== structural equality).
class Expr {
 public:
  Expr();  // the number 0
  explicit Expr(const Node* node) : node_(node) {}
  Expr(int value);              // NOLINT(google-explicit-constructor)
  Expr(std::int64_t value);     // NOLINT(google-explicit-constructor): numbers read naturally in formulas
  Expr(const Rational& value);  // NOLINT(google-explicit-constructor)

  [[nodiscard]] const Node* node() const { return node_; }
  [[nodiscard]] Kind kind() const;
  [[nodiscard]] std::size_t hash() const;
  [[nodiscard]] bool is_number() const { return kind() == Kind::Number; }
  [[nodiscard]] bool is_zero() const;
  [[nodiscard]] bool is_one() const;
  [[nodiscard]] bool is_symbol() const { return kind() == Kind::Symbol; }
  /// Number value, Add constant term, or Mul coefficient; 0 for other kinds.
  [[nodiscard]] const Rational& value() const;
  /// Symbol or constant name; empty for other kinds.
  [[nodiscard]] const std::string& name() const;
  /// Add terms, Mul bases, function arguments.
  [[nodiscard]] std::span<const Expr> args() const;
  /// Add coefficients or Mul exponents, parallel to args(); empty for functions.
  [[nodiscard]] std::span<const Rational> weights() const;
  /// Number of distinct nodes reachable from this one (DAG size).
  [[nodiscard]] std::size_t dag_size() const;

  friend bool operator==(Expr a, Expr b) { return a.node_ == b.node_; }

 private:
  const Node* node_;
};

struct ExprHash {
  std::size_t operator()(Expr e) const { return e.hash(); }
};

// ---- constructors (all return canonical, interned nodes) ----
Expr number(const Rational& value);
Expr symbol(std::string_view name);
Expr pi();
Expr add(std::span<const Expr> terms);
Expr mul(std::span<const Expr> factors);
Expr pow(Expr base, int exponent);
Expr sin(Expr arg);
Expr cos(Expr arg);
Expr sqrt(Expr arg);
Expr atan2(Expr y, Expr x);

/// A sum built from (coefficient, term) pairs without intermediate nodes.
Expr linear_combination(std::span<const std::pair<Rational, Expr>> terms, const Rational& constant = Rational(0));

Expr operator+(Expr a, Expr b);
Expr operator-(Expr a, Expr b);
Expr operator*(Expr a, Expr b);
Expr operator/(Expr a, Expr b);
Expr operator-(Expr a);
inline Expr& operator+=(Expr& a, Expr b) { return a = a + b; }
inline Expr& operator-=(Expr& a, Expr b) { return a = a - b; }
inline Expr& operator*=(Expr& a, Expr b) { return a = a * b; }

/// Splits e into (c, rest) with e == c*rest and rest carrying no numeric factor.
std::pair<Rational, Expr> split_coefficient(Expr e);

/// True when the canonical sign of e is negative (used to normalise odd functions).
bool has_negative_sign(Expr e);

/// Deterministic total order used for canonical operand order.
bool canonical_less(Expr a, Expr b);

/// Symbols (not constants) occurring in e, sorted by name (natural order: q2 < q10).
std::vector<Expr> free_symbols(Expr e);
bool depends_on(Expr e, Expr symbol);

/// Natural ordering of names so that q2 sorts before q10.
bool natural_less(std::string_view a, std::string_view b);

/// Number of nodes in the pool (for diagnostics and benchmarks).
std::size_t pool_size();

}  // namespace dyncc::sym

template <>
struct std::hash<dyncc::sym::Expr> {
  std::size_t operator()(dyncc::sym::Expr e) const { return e.hash(); }
};
