// alpha_mask.cpp — the alpha rule's GLSL (alpha_mask.hpp), beside the C++ it mirrors operation for
// operation: change one, change both (renderer_test's texel-by-texel check holds them together).
#include "shadowref/scene/alpha_mask.hpp"

namespace shadowref::scene {

const char* alpha_rule_glsl() {
  return R"glsl(
// The alpha rule (scene/alpha_mask.hpp): NEAREST texel with REPEAT, opaque when a8 * a_v >= threshold.
int alpha_texel(float t, int size) {
  float f = t - floor(t);
  return min(int(f * float(size)), size - 1);
}
bool alpha_opaque(uint a8, float vertex_alpha, float threshold) {
  return float(a8) * vertex_alpha >= threshold;
}
)glsl";
}

}  // namespace shadowref::scene
