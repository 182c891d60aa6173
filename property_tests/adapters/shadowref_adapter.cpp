// The math properties run on shadowref's own mathlib.
#include "adapters/shadowref_adapter.hpp"

namespace shadowref::prop {

const MathAdapter& math_adapter_under_test() {
  static const MathAdapter adapter = shadowref_math_adapter();
  return adapter;
}

}  // namespace shadowref::prop
