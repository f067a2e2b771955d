// Lowering: canonical expressions (sym::Expr) -> the straight-line program (codegen::Program).
//
// What happens on the way, and why:
//  - sums and products become chains of binary operations; a product's factors are ordered so
//    that the values computed first (sin/cos of the coordinates, inputs) come first, which lets
//    monomials that share leading factors share the partial products;
//  - sums are factored greedily (Horner's scheme for several variables): the factor shared by
//    most terms is taken out, recursively, and terms with the same numeric coefficient share one
//    multiplication by it;
//  - integer powers become multiplications by repeated squaring; x^-n a division;
//  - sin and cos of a sum or an integer multiple of angles are expanded by the product formulas
//    (sin(q3 - q2) = s3*c2 - c3*s2), so each coordinate's sin and cos is computed once;
//  - everything without a symbol is folded to a number as it is built.
#pragma once

#include <string>
#include <unordered_map>

#include "codegen/ir.hpp"
#include "sym/bindings.hpp"
#include "sym/expr.hpp"

namespace dyncc::codegen {

class Lowering {
 public:
  /// inputs: symbol -> the C expression it is read from (e.g. q1 -> "q[0]").
  Lowering(Program& program, std::unordered_map<sym::Expr, std::string> inputs);

  ValueId operator()(sym::Expr e);

  /// Bound symbols (sym/bindings.hpp) are lowered as their definitions, each once.
  void define(const sym::Bindings& bindings);

 private:
  // A term of a sum as coefficient * product of factors^exponents (positive integers); a term
  // that is not such a product is one factor.
  struct Monomial {
    sym::Rational coefficient;
    std::vector<std::pair<sym::Expr, int>> factors;
  };
  // A value and whether the sum it stands for is its negative (signs are carried up to the
  // enclosing sum, where they become subtractions instead of negations).
  struct Signed {
    ValueId value = -1;
    bool negative = false;
  };
  ValueId lower_sum(sym::Expr e);
  Signed factorize(std::vector<Monomial> terms);
  Signed plain_sum(const std::vector<Monomial>& terms);
  ValueId monomial_body(const Monomial& m);
  ValueId lower_product(sym::Expr e);
  ValueId product_of(std::vector<ValueId> factors);
  ValueId sin_of(sym::Expr angle);
  ValueId cos_of(sym::Expr angle);
  /// sin (want_sin) or cos of angle, expanded by the angle-sum formulas.
  ValueId trig_of(sym::Expr angle, bool want_sin);
  ValueId angle_sum(ValueId sa, ValueId ca, ValueId sb, ValueId cb, bool want_sin);

  Program& program_;
  std::unordered_map<sym::Expr, std::string> inputs_;
  std::unordered_map<sym::Expr, sym::Expr> definitions_;
  std::unordered_map<sym::Expr, ValueId> memo_;
  std::unordered_map<sym::Expr, ValueId> sin_memo_, cos_memo_;
};

}  // namespace dyncc::codegen
