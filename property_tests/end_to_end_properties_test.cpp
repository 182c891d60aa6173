// end_to_end_properties_test.cpp — no shadow is seen from the light's position, end to end.
//
// Small random scenes (a ground receiver and one to three boxes and spheres over it, one point
// light above), rendered with the camera AT the light, looking at the scene:
//   * the Embree reference's mask has no shadowed pixel (among its decided pixels: a pixel the
//     reference itself calls undecided, a silhouette grazed by the view, may honestly go either way);
//   * every technique of the OpenGL renderer (OSMesa, llvmpipe) shows none on those pixels.
// (The stencil-count form of the law, z-pass = 0 from the light, is in volume_properties_test.cpp.)
// Rendering is costly: these run max_success / 200 cases (5 by default), at 32 × 32 pixels, and a
// failing case is not shrunk (each shrink step is a render); it prints its scene and reproduce string.
#include <cstdlib>
#include <map>
#include <memory>
#include <set>

#include "generators.hpp"
#include "property_support.hpp"
#include "shadowref/primitives.hpp"
#include "shadowref/reference/render.hpp"
#include "shadowref/renderer/renderer.hpp"

namespace shadowref::prop {
namespace {

constexpr int kCaseDivisor = 200;  // rendered properties run max_success / 200 cases (5 by default)
constexpr int kSize = 32;         // pixels per side

struct SceneCase {
  scene::Scene scene;
  friend std::ostream& operator<<(std::ostream& os, const SceneCase& c) {
    const auto& cam = c.scene.camera;
    os << "scene: camera (= light) at " << str(cam.position) << " looking at " << str(cam.target) << "; objects:";
    for (const auto& o : c.scene.objects) os << " " << o.name << " (" << o.mesh.triangles.size() << " triangles)";
    return os;
  }
};

TriangleMesh<float> moved(TriangleMesh<float> m, const Vec3<float>& by) {
  for (auto& p : m.positions) p += by;
  return m;
}

// A small random scene with the camera at the point light.
rc::Gen<SceneCase> scene_from_the_light() {
  const auto object = rc::gen::apply(
      [](bool sphere, const Vec3<double>& at, double size) {
        const Vec3<float> pos(static_cast<float>(at.x()), static_cast<float>(size + 0.5 * (at.y() + 2)), static_cast<float>(at.z()));
        scene::Object o;
        o.name = sphere ? "sphere" : "box";
        o.shape = o.name;
        const auto s = static_cast<float>(size);
        o.mesh = moved(sphere ? make_uv_sphere(s, 16u, 8u).value() : make_box(Vec3<float>(-s, -s, -s), Vec3<float>(s, s, s)).value(), pos);
        return o;
      },
      rc::gen::arbitrary<bool>(), gen::vec3(2.5), gen::uniform(0.3, 1));
  return rc::gen::apply(
      [](const std::vector<scene::Object>& casters, const Vec3<double>& light_xz, double height, const Vec3<double>& look) {
        SceneCase c;
        auto& s = c.scene;
        s.name = "from_the_light";
        s.width = s.height = kSize;
        scene::Object ground;
        ground.name = ground.shape = "plane";
        ground.mesh = make_plane(10.0f, 10.0f).value();
        ground.receiver = true;
        s.objects.push_back(ground);
        for (const auto& o : casters) s.objects.push_back(o);
        scene::Light light;
        light.type = scene::LightType::Point;
        light.position = Vec3<double>(light_xz.x(), height, light_xz.z());
        s.lights.push_back(light);
        s.camera.position = light.position;
        s.camera.target = Vec3<double>(look.x(), 0, look.z());
        s.camera.up = Vec3<double>(0.0137, 0.0291, 1).normalized();  // never parallel: the view looks down
        s.camera.fovy_deg = 70;
        s.camera.near = 0.05;
        return c;
      },
      rc::gen::mapcat(rc::gen::inRange<std::size_t>(1, 4),
                      [object](std::size_t n) { return rc::gen::container<std::vector<scene::Object>>(n, object); }),
      gen::vec3(3), gen::uniform(4, 9), gen::vec3(2));
}

// Pixels where a shadowed mask value would break the law: decided by the reference, with a surface.
int shadowed_pixels(const std::vector<std::uint8_t>& mask, const reference::Images& ref, const std::string& who) {
  int shadowed = 0;
  for (std::size_t i = 0; i < mask.size(); ++i)
    if (mask[i] == 0 && ref.decided[i] == 255) ++shadowed;
  RC_LOG() << who << ": " << shadowed << " decided shadowed pixels\n";
  return shadowed;
}

void assert_no_shadow(const std::vector<std::uint8_t>& mask, const reference::Images& ref, const std::string& who) {
  RC_ASSERT(shadowed_pixels(mask, ref, who) == 0);
}

// Techniques this property catches today and whose finding is still open (none): listed ones are
// counted and printed instead of asserted, unless SHADOWREF_E2E_STRICT=1. History (the first report):
//   * shadowmap, shadowmap-pcf, shadowmap-rgba8 showed shadowed pixels from the light's position
//     when the scene's bounds did not fit in one light frustum of at most 160 degrees; fixed by the
//     cube shadow map for such point lights (renderer/shadow_maps/light_map.cpp, mathlib/include/shadowref/light_fit.hpp);
//   * planar showed 1 to 5 pixels on casters' silhouettes: pixels whose sub-pixel samples see two
//     surfaces (the projected shadow's outline is the caster's own outline seen from the light, up
//     to float rounding), which the reference now calls undecided.
const std::set<std::string> kKnownFailures = {};

reference::Images reference_images(const scene::Scene& s) {
  reference::Options opt;
  opt.samples_per_axis = 2;
  opt.threads = 1;
  return reference::render(s, opt);
}

TEST(EndToEndProperties, reference_sees_no_shadow_from_the_light) {
  check_property(
      [] {
        const auto c = *scene_from_the_light();
        const auto ref = reference_images(c.scene);
        assert_no_shadow(ref.lights[0].mask, ref, "reference");
      },
      scaled_cases(kCaseDivisor), false);
}

TEST(EndToEndProperties, every_renderer_technique_sees_no_shadow_from_the_light) {
  std::unique_ptr<renderer::Renderer> gl;
  try {
    gl = std::make_unique<renderer::Renderer>(renderer::GlApi::OSMesa, renderer::Driver::Llvmpipe);
  } catch (const std::exception& e) {
    // scripts/setup.sh installs OSMesa: a missing context is a broken set-up, not a reason to skip.
    FAIL() << "no OpenGL context: " << e.what();
  }
  const bool strict = std::getenv("SHADOWREF_E2E_STRICT") != nullptr;
  std::map<std::string, int> known_failure_pixels;
  check_property(
      [&] {
        const auto c = *scene_from_the_light();
        const auto ref = reference_images(c.scene);
        for (const auto& t : renderer::techniques()) {
          const auto res = gl->render(c.scene, t.name);
          RC_ASSERT(!res.masks.empty());
          const std::string name(t.name);
          const int n = shadowed_pixels(res.masks[0].pixels, ref, name);
          if (kKnownFailures.count(name) && !strict) {
            known_failure_pixels[name] += n;
            continue;
          }
          RC_ASSERT(n == 0);
        }
      },
      scaled_cases(kCaseDivisor), false);
  for (const auto& name : kKnownFailures) {
    std::cout << "known failure " << name << ": " << known_failure_pixels[name]
              << " decided shadowed pixels seen from the light over all cases\n";
  }
}

}  // namespace
}  // namespace shadowref::prop
