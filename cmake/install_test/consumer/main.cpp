// A program of an engine team's own, built against an installed shadowref (CMake or pkg-config):
// the worked example of the top-level README, the ground y = 0 and a point light at (2, 6, 1).
// Exits 0 when the point (1, 3, 0) lands on the ground at (0, 0, -1).
#include <shadowref/shadow_matrix.hpp>

#include <cstdio>

int main() {
  const shadowref::Plane<double> ground{shadowref::Vec4<double>(0, 1, 0, 0)};
  const auto s = shadowref::shadow_matrix(ground, shadowref::Vec4<double>(2, 6, 1, 1));
  if (!s) {
    std::printf("shadow_matrix: %s\n", s.message());
    return 1;
  }
  const shadowref::Vec4<double> p = *s * shadowref::Vec4<double>(1, 3, 0, 1);
  std::printf("S (1, 3, 0, 1) = (%g, %g, %g, %g)\n", p.x(), p.y(), p.z(), p.w());
  // Every entry is a small integer, exact in binary: compared exactly.
  return p == shadowref::Vec4<double>(0, 0, -3, 3) ? 0 : 1;
}
