// Emission of one straight-line program as the body of a C++ function template on the scalar S.
//
// A value used more than once becomes a named `const S` temporary; a value used once is written
// inline where it is used, so the text stays close to the size of the computation. Evaluation
// order is exactly the program's (parentheses keep every binary operation as built), so the
// float and double instantiations compute what was counted.
#pragma once

#include <string>
#include <vector>

#include "codegen/model_functions.hpp"

namespace dyncc::codegen {

struct RenderedFunction {
  std::string body;                  // statements, indented two spaces, one per line
  OpCounts counts;                   // over the program's live values
  std::vector<bool> parameter_used;  // parallel to Function::parameters
  int temporaries = 0;
};

RenderedFunction render_body(const Function& f);

/// A double as a C++ literal of the scalar type: S(0.18), S(-2), shortest text that round-trips.
std::string scalar_literal(double value);

}  // namespace dyncc::codegen
