// zigzag_properties_test.cpp — the zigzag certificate (tolerance/zigzags.hpp, no_grid_gives) never
// holds for a correct shadow map's answers: over generated rectangular texel grids (any turn,
// texel size per axis and phase: every orthographic view of a directional light), generated
// straight caster edges and the lookups engines use — nearest, a fixed 3 × 3 box at a 1/2
// threshold, bilinear PCF at 1/2, a fixed kernel of 5 arbitrary taps at 1/2 — no three answers
// near the edge are certified. And its teeth: the answers a swapped tile leaves across such an edge
// are certified; and a skewed grid (a perspective warp's cells) can fold its staircase back, which
// is why the check is for orthographic views alone.
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "generators.hpp"
#include "property_support.hpp"
#include "shadowref/tolerance/zigzags.hpp"

namespace shadowref::prop {
namespace {

using tolerance::EdgePoint;
using tolerance::no_grid_gives;

enum class Lookup { Nearest, Box3, Bilinear, FixedKernel };

struct GridCase {
  double turn = 0, axes = 90;       // the first axis's angle and the angle between the axes (degrees)
  double spacing1 = 1, spacing2 = 1;  // texel sizes along the axes
  double phase1 = 0, phase2 = 0;
  double edge = 0, offset = 0;      // the edge's normal angle (degrees, into the shadow) and offset
  Lookup lookup = Lookup::Nearest;
  std::vector<std::array<double, 2>> kernel;  // FixedKernel's taps, in texels
  std::vector<std::array<double, 2>> points;  // where answers are asked, in (e, s) of the edge
};

std::ostream& operator<<(std::ostream& os, const GridCase& c) {
  return os << "turn " << c.turn << "°, axes " << c.axes << "° apart, spacings " << c.spacing1 << ", " << c.spacing2 << ", phase "
            << c.phase1 << ", " << c.phase2 << ", edge normal " << c.edge << "°, offset " << c.offset << ", lookup "
            << static_cast<int>(c.lookup) << ", " << c.points.size() << " points";
}

rc::Gen<GridCase> grid_case(double min_axes, double max_axes) {
  return rc::gen::exec([min_axes, max_axes] {
    GridCase c;
    c.turn = *gen::uniform(0, 180);
    c.axes = *gen::uniform(min_axes, max_axes);
    c.spacing1 = *gen::uniform(0.2, 5);
    c.spacing2 = *gen::uniform(0.2, 5);
    c.phase1 = *gen::uniform(0, 1);
    c.phase2 = *gen::uniform(0, 1);
    c.edge = *gen::uniform(0, 360);
    c.offset = *gen::centered(3);
    c.lookup = static_cast<Lookup>(*rc::gen::inRange(0, 4));
    for (int i = 0; i < 5; ++i) c.kernel.push_back({*gen::centered(2), *gen::centered(2)});
    // Answers asked within three of the larger texels of the edge, along four of them.
    const double band = 3 * std::max(c.spacing1, c.spacing2), along = 4 * std::max(c.spacing1, c.spacing2);
    for (int i = 0; i < 40; ++i) c.points.push_back({*gen::centered(along), *gen::centered(band)});
    return c;
  });
}

// The case's answers at its points: the lookup over the grid's texels, each shadowed when its
// centre lies on the shadow side of the edge (a digital half-plane: what a map of a straight caster
// edge over one receiver holds).
std::vector<EdgePoint> answers(const GridCase& c) {
  const double r = std::numbers::pi / 180.0;
  const std::array<double, 2> n{std::cos(c.edge * r), std::sin(c.edge * r)}, e{-n[1], n[0]};
  const std::array<double, 2> a1{c.spacing1 * std::cos(c.turn * r), c.spacing1 * std::sin(c.turn * r)};
  const std::array<double, 2> a2{c.spacing2 * std::cos((c.turn + c.axes) * r), c.spacing2 * std::sin((c.turn + c.axes) * r)};
  const double det = a1[0] * a2[1] - a1[1] * a2[0];
  // A texel (i, j) is shadowed when its centre (i + 1/2 − phase along each axis) is past the edge.
  const auto shadowed = [&](double i, double j) {
    const double u = i + 0.5 - c.phase1, v = j + 0.5 - c.phase2;
    const double x = u * a1[0] + v * a2[0], y = u * a1[1] + v * a2[1];
    return n[0] * x + n[1] * y > c.offset ? 1.0 : 0.0;
  };
  std::vector<EdgePoint> out;
  for (const auto& p : c.points) {
    const double x = p[0] * e[0] + p[1] * n[0], y = p[0] * e[1] + p[1] * n[1];
    // Grid coordinates: q = (g1 − phase1) a1 + (g2 − phase2) a2.
    const double g1 = (x * a2[1] - y * a2[0]) / det + c.phase1, g2 = (a1[0] * y - a1[1] * x) / det + c.phase2;
    double value = 0;
    switch (c.lookup) {
      case Lookup::Nearest: value = shadowed(std::floor(g1), std::floor(g2)); break;
      case Lookup::Box3:
        for (int dj = -1; dj <= 1; ++dj)
          for (int di = -1; di <= 1; ++di) value += shadowed(std::floor(g1) + di, std::floor(g2) + dj) / 9.0;
        break;
      case Lookup::Bilinear: {
        const double b1 = g1 - 0.5, b2 = g2 - 0.5, f1 = b1 - std::floor(b1), f2 = b2 - std::floor(b2);
        const double i = std::floor(b1), j = std::floor(b2);
        value = (1 - f1) * (1 - f2) * shadowed(i, j) + f1 * (1 - f2) * shadowed(i + 1, j) + (1 - f1) * f2 * shadowed(i, j + 1) +
                f1 * f2 * shadowed(i + 1, j + 1);
        break;
      }
      case Lookup::FixedKernel:
        for (const auto& k : c.kernel) value += shadowed(std::floor(g1 + k[0]), std::floor(g2 + k[1])) / static_cast<double>(c.kernel.size());
        break;
    }
    out.push_back({p[0], p[1], value >= 0.5});
  }
  std::sort(out.begin(), out.end(), [](const EdgePoint& a, const EdgePoint& b) { return a.e < b.e; });
  return out;
}

// The first certified triple of the case's answers, if any.
bool any_certified(const std::vector<EdgePoint>& a) {
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = i + 1; j < a.size(); ++j)
      for (std::size_t k = j + 1; k < a.size(); ++k)
        if (no_grid_gives(a[i], a[j], a[k])) return true;
  return false;
}

// Every rectangular grid: axes 90° apart, any turn, sizes and phase.
RC_GTEST_PROP(ZigzagProperties, NoCorrectMapIsCertified, ()) {
  const GridCase c = *grid_case(90.0, 90.0);
  RC_ASSERT(!any_certified(answers(c)));
}

// The tooth: the answers a tile swapped across a straight edge leaves (a lit block past the
// boundary, shadow beyond it again) are certified on any grid.
TEST(ZigzagCertificate, ASwappedTileIsCertified) {
  // Shadowed beyond s = 0 along the edge; the tile moved the lit side 4 units into the shadow over
  // e in [0, 4], and the shadow 4 units out beyond it.
  const EdgePoint shadow_near{0.9, 0.5, true}, lit_deep{1.0, 3.0, false}, shadow_far{1.1, 0.5, true};
  EXPECT_TRUE(no_grid_gives(shadow_near, lit_deep, shadow_far));
  const EdgePoint lit_a{1.9, 0.5, false}, shadow_out{2.0, -3.0, true}, lit_b{2.1, 0.5, false};
  EXPECT_TRUE(no_grid_gives(lit_a, shadow_out, lit_b));
  // The same three spread along the edge by more than a staircase needs to come back: not certified.
  EXPECT_FALSE(no_grid_gives({-3.0, 0.5, true}, {0.0, 3.0, false}, {3.0, 0.5, true}));
  // A staircase's one step (no way back) is never a zigzag.
  EXPECT_FALSE(no_grid_gives({0.9, 0.5, true}, {1.0, 3.0, false}, {1.1, 3.5, false}));
}

// Why the check is for rectangular grids: a grid skewed as a perspective warp skews its cells (axes
// 30° to 60° apart) gives correct answers that fold back along the edge's normal, and some are
// certified — so a warped map must declare its matrices. (The property above is not vacuous.)
TEST(ZigzagCertificate, SkewedGridsFoldBack) {
  int certified = 0;
  for (int seed = 0; seed < 2000 && certified == 0; ++seed) {
    GridCase c = grid_case(30.0, 60.0)(rc::Random(static_cast<std::uint64_t>(seed)), 100).value();
    c.lookup = Lookup::Nearest;
    certified += any_certified(answers(c));
  }
  EXPECT_GT(certified, 0) << "no skewed grid's staircase folded back: the certificate's rectangular premise would be untested";
}

}  // namespace
}  // namespace shadowref::prop
