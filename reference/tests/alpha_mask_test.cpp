// alpha_mask_test.cpp — an independent check of the reference's alpha test: a masked card over a
// ground plane, and every decided ground pixel of the reference's mask must be the card's texel
// carried onto the ground by mathlib's planar shadow matrix (shadow_matrix.hpp), found here without
// any of the reference's code: the pixel's ray meets the ground in double, the inverse of the
// homography that the shadow matrix makes of the card's plane gives the card point, and its texel is
// floor(u · 8), floor(v · 8). A directional light (S affine on the card) and a point light (S
// projective) both.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <nlohmann/json.hpp>
#include <cmath>
#include <filesystem>
#include <string>

#include "shadowref/outputs/image_io.hpp"
#include "shadowref/plane.hpp"
#include "shadowref/reference/render.hpp"
#include "shadowref/scene/camera.hpp"
#include "shadowref/scene/load_scene.hpp"
#include "shadowref/shadow_matrix.hpp"

namespace shadowref::reference {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr int kTexels = 8;
constexpr double kCardHalf = 1.0;           // the card is 2 × 2, at height kCardHeight
constexpr double kCardHeight = 1.0;
constexpr double kGroundHalf = 6.0;         // the ground is 12 × 12 around the origin
const Vec3<double> kCardCentre(0.3, kCardHeight, -0.2);

// The mask: a deterministic pattern with both kinds of texel next to each other everywhere.
std::uint8_t texel_alpha(int i, int j) { return ((i * 5 + j * 3 + (i * j) % 4) % 7) < 3 ? 0 : 255; }

// Solves the homography taking the card's (u, v) to ground (x, z) from four correspondences (h33 = 1).
Eigen::Matrix3d homography(const std::array<Vec2<double>, 4>& from, const std::array<Vec2<double>, 4>& to) {
  Eigen::Matrix<double, 8, 8> a;
  Eigen::Matrix<double, 8, 1> b;
  for (int k = 0; k < 4; ++k) {
    const double u = from[k].x(), v = from[k].y(), x = to[k].x(), y = to[k].y();
    a.row(2 * k) << u, v, 1, 0, 0, 0, -u * x, -v * x;
    a.row(2 * k + 1) << 0, 0, 0, u, v, 1, -u * y, -v * y;
    b(2 * k) = x;
    b(2 * k + 1) = y;
  }
  const Eigen::Matrix<double, 8, 1> h = a.fullPivLu().solve(b);
  Eigen::Matrix3d m;
  m << h(0), h(1), h(2), h(3), h(4), h(5), h(6), h(7), 1;
  return m;
}

class AlphaIndependentCheck : public ::testing::TestWithParam<const char*> {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) / "shadowref-alpha-independent";
    fs::create_directories(dir_);
    outputs::Image8 mask{kTexels, kTexels, 1, {}};
    for (int j = 0; j < kTexels; ++j)
      for (int i = 0; i < kTexels; ++i) mask.pixels.push_back(texel_alpha(i, j));
    outputs::write_png(mask, dir_ / "mask.png");
  }
  fs::path dir_;
};

TEST_P(AlphaIndependentCheck, DecidedPixelsAreTheCardsTexelsThroughTheShadowMatrix) {
  const bool directional = std::string(GetParam()) == "directional";
  const json light = directional ? json{{"type", "directional"}, {"direction", {0.3, 1, 0.2}}}
                                 : json{{"type", "point"}, {"position", {0.4, 5, 0.8}}};
  const json doc = {
      {"name", "alpha_independent"},
      {"resolution", {160, 160}},
      {"camera", {{"position", {0, 6, 4.5}}, {"target", {0, 0, -0.3}}, {"fovy_deg", 45}, {"near", 0.1}}},
      {"lights", {light}},
      {"objects",
       {{{"name", "ground"}, {"shape", {{"type", "plane"}, {"size", {2 * kGroundHalf, 2 * kGroundHalf}}}}, {"receiver", true}},
        {{"name", "card"},
         {"shape", {{"type", "plane"}, {"size", {2 * kCardHalf, 2 * kCardHalf}}}},
         {"transform", {{"translate", {kCardCentre.x(), kCardCentre.y(), kCardCentre.z()}}}},
         // make_plane's vertex order: (-x, -z), (+x, -z), (+x, +z), (-x, +z).
         {"uvs", {{0, 0}, {1, 0}, {1, 1}, {0, 1}}},
         {"alpha_texture", "mask.png"},
         {"alpha_cutoff", 0.5}}}}};
  const scene::Scene s = scene::parse_scene(doc.dump(), dir_ / "scene.json");
  const Images img = render(s);

  // The card's corners (uv) and where the shadow matrix puts them on the ground (x, z).
  const Plane<double> ground = plane_from_coefficients<double>(0, 1, 0, 0).value();
  const Mat4<double> S = shadow_matrix(ground, scene::homogeneous(s.lights[0])).value();
  std::array<Vec2<double>, 4> uv, carried;
  for (int k = 0; k < 4; ++k) {
    const double u = k == 1 || k == 2 ? 1 : 0, v = k >= 2 ? 1 : 0;
    uv[k] = Vec2<double>(u, v);
    const Vec3<double> corner = kCardCentre + Vec3<double>((2 * u - 1) * kCardHalf, 0, (2 * v - 1) * kCardHalf);
    const Vec4<double> g = S * corner.homogeneous();
    carried[k] = Vec2<double>(g.x() / g.w(), g.z() / g.w());
  }
  const Eigen::Matrix3d ground_to_uv = homography(uv, carried).inverse();

  // Each pixel's ray in double, from the same camera matrices (scene/camera.hpp).
  const Mat4<double> clip_from_world = scene::projection_matrix<double>(s.camera, s.width, s.height).value() *
                                       scene::view_matrix<double>(s.camera).value();
  const Mat4<double> world_from_clip = clip_from_world.inverse();
  int compared = 0, shadowed_in_card = 0, lit_in_card = 0, mismatched = 0;
  std::string first_mismatch;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(s.width) + static_cast<std::size_t>(x);
      if (!img.lights[0].decided[i]) continue;
      const Vec2<double> ndc = scene::pixel_to_ndc<double>(x, y, 0.5, 0.5, s.width, s.height);
      const Vec4<double> a = world_from_clip * Vec4<double>(ndc.x(), ndc.y(), -1, 1);
      const Vec4<double> b = world_from_clip * Vec4<double>(ndc.x(), ndc.y(), 0, 1);
      const Vec3<double> o = a.head<3>() / a.w(), d = (b.head<3>() / b.w() - o).normalized();
      if (!(d.y() < 0)) continue;
      // Pixels whose ray crosses the card's square are left out: they see the card, or the ground
      // through its holes, which this check does not model.
      const double t_card = (kCardHeight - o.y()) / d.y();
      const Vec3<double> on_card = o + t_card * d;
      if (std::abs(on_card.x() - kCardCentre.x()) <= kCardHalf && std::abs(on_card.z() - kCardCentre.z()) <= kCardHalf) continue;
      const Vec3<double> p = o + (-o.y() / d.y()) * d;  // on the ground's plane
      if (std::abs(p.x()) >= kGroundHalf || std::abs(p.z()) >= kGroundHalf) continue;  // beyond it: the sky
      const Vec3<double> h = ground_to_uv * Vec3<double>(p.x(), p.z(), 1);
      const double u = h.x() / h.z(), v = h.y() / h.z();
      bool shadowed = false;
      if (u >= 0 && u < 1 && v >= 0 && v < 1) {
        const int ti = static_cast<int>(std::floor(u * kTexels)), tj = static_cast<int>(std::floor(v * kTexels));
        shadowed = texel_alpha(ti, tj) >= 128;  // 0 lets light through; 255 casts (cutoff 0.5)
        (shadowed ? shadowed_in_card : lit_in_card) += 1;
      }
      ++compared;
      const std::uint8_t expected = shadowed ? outputs::kMaskShadowed : outputs::kMaskLit;
      if (img.lights[0].mask[i] != expected) {
        if (mismatched++ == 0)
          first_mismatch = "pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") at uv (" + std::to_string(u) + ", " +
                           std::to_string(v) + "): reference " + std::to_string(img.lights[0].mask[i]) + ", expected " +
                           std::to_string(expected);
      }
    }
  EXPECT_EQ(mismatched, 0) << first_mismatch;
  // Not vacuous: the card's shadow is on screen, decided, with both kinds of texel in it (each texel
  // of the visible part carried onto some 20 pixels; hundreds of each kind, 3 of 7 texels clear).
  EXPECT_GT(compared, 5000);
  EXPECT_GT(shadowed_in_card, 200);
  EXPECT_GT(lit_in_card, 200);
}

INSTANTIATE_TEST_SUITE_P(Reference, AlphaIndependentCheck, ::testing::Values("directional", "point"),
                         [](const ::testing::TestParamInfo<const char*>& p) { return std::string(p.param); });

}  // namespace
}  // namespace shadowref::reference
