#include "sym/simplify.hpp"

#include <stdexcept>

#include "sym/expand.hpp"
#include "sym/trig_normal_form.hpp"

namespace dyncc::sym {

Expr simplify(Expr e) {
  Expr best = e;
  std::size_t best_size = e.dag_size();
  auto consider = [&](Expr candidate) {
    const std::size_t size = candidate.dag_size();
    if (size < best_size) {
      best = candidate;
      best_size = size;
    }
  };
  consider(expand(e));
  try {
    consider(trig_normal_form(e).expr);
  } catch (const std::overflow_error&) {
    // Too large for the exact normal form: keep the other candidates.
  }
  return best;
}

}  // namespace dyncc::sym
