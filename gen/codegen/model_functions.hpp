// What the generated code computes, as straight-line programs: H, C, tau_g, friction, the
// regressor in both forms, the fused Slotine-Li torque and adaptation term, the fused control
// step, and the base parameters from the link parameters.
//
// Everything is written in the BASE parameters p (the identifiable combinations): the base
// regressor column of p_b is the regressor column of the standard parameter it keeps, and
// tau = sum_b p_b * Y_b. H and C follow as dtau/da and dtau/dv, so every function agrees with the
// regressor by construction, and the parameter vector a controller adapts is the one H, C and g
// are evaluated with.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "codegen/ir.hpp"
#include "pipeline/derivation.hpp"

namespace dyncc::codegen {

struct Function {
  std::string name;                           // C++ function name
  std::string summary;                        // one line for the doc comment
  std::vector<std::string> parameters;        // "q", "qd", ... in signature order
  std::vector<bool> parameter_is_output;      // parallel: written (S*) or read (const S*)
  std::map<std::string, std::string> labels;  // input C expression -> readable name (q[0] -> q1)
  Program program;
};

struct ModelFunctions {
  std::vector<Function> functions;
  /// The same inverse dynamics, mass matrix, Coriolis matrix, gravity and regressor over all
  /// STANDARD parameters (one symbol each): not emitted, only counted, for comparison with tools
  /// that generate code in that parameterisation (SymPyBotics).
  std::vector<Function> standard_parameter_variants;
};

ModelFunctions build_model_functions(const pipeline::Derivation& derivation);

}  // namespace dyncc::codegen
