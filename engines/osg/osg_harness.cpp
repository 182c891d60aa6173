// engines/osg/osg_harness.cpp — renders an exported pack with OpenSceneGraph's osgShadow shadow maps,
// the way an OSG user would, and writes a candidate folder: <out>/<scene>/mask.png (mask_<i>.png per
// light, one render per light) and candidate.json. --variant shadowmap (osgShadow::ShadowMap, judged
// as shadowmap), softshadowmap (osgShadow::SoftShadowMap, judged as shadowmap-pcf) or the control
// shadowmap-no-offset (below).
//
// How the pack becomes an OSG scene (engines/README.md says why):
//   * Meshes: OSG's own OBJ plugin with "noRotation" (it turns models z-up otherwise); the harness
//     takes their triangles (osg::TriangleFunctor) into geometry with one vertex per face corner, so
//     that faces can have their own colour.
//   * Camera: the pack's gl view and finite projection, as they are (OSG is right-handed and takes
//     row-vector matrices: the pack's D3DX layout); near/far computation off. The techniques fit
//     their own light views: ShadowMap's fit is part of what is judged, and the harness declares the
//     matrices it drew with (light_views "declared": its shadow camera's view and projection after
//     the frame, read through ReadableShadowMap).
//   * Lights: an osg::LightSource at the pack's homogeneous light (w = 0: directional). Spot and
//     rect lights are their point (spot cut-off 180): the mask is occlusion only, the cone is lighting.
//   * Materials: lighting off, vertex colours; faces turned away from the light are painted black by
//     the harness (attached_shadow.hpp), all else white. The technique's ambient bias is (0, 1), so
//     the shadow test alone scales the colour: 1 lit, 0 shadowed, greys where it filters.
//   * Everything else is the technique's default: 1024² map, front faces culled in the depth pass,
//     glPolygonOffset(-1, -1), bilinear depth compare; SoftShadowMap's softness 0.005 and its 64 taps
//     of a random 3D texture (declared as a random kernel of 8 x 8 taps).
//   * The control (shadowmap-no-offset): ShadowMap with setPolygonOffset(0, 0), its one public knob
//     that the default runs' failures point at (ShadowMap::init applies the *negated* offset). Nothing
//     else changes, so where the control passes and the default fails, the harness is not the cause.
#include <osg/Camera>
#include <osg/Geode>
#include <osg/Geometry>
#include <osg/LightSource>
#include <osg/NodeVisitor>
#include <osg/TriangleFunctor>
#include <osg/Version>
#include <osgDB/Options>
#include <osgDB/ReadFile>
#include <osgShadow/ShadowMap>
#include <osgShadow/ShadowedScene>
#include <osgShadow/SoftShadowMap>
#include <osgViewer/Viewer>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "attached_shadow.hpp"
#include "harness_args.hpp"
#include "mask_output.hpp"
#include "pack_scene.hpp"

namespace {

using engines::Mat4;

constexpr int kMapSize = 1024;            // ShadowMap's default texture size
constexpr float kSoftnessWidth = 0.005f;  // SoftShadowMap's default, in shadow-texture coordinates
constexpr int kSoftTaps = 8;              // SoftShadowMap's shader: SAMPLECOUNT 64 jittered taps, 8 per axis

// OSG matrices are row-vector (v' = v M): the transpose of the canonical layout.
osg::Matrixd to_osg(const Mat4& m) {
  osg::Matrixd out;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out(r, c) = m[static_cast<std::size_t>(c)][static_cast<std::size_t>(r)];
  return out;
}

struct CollectTriangle {
  std::vector<osg::Vec3d>* out = nullptr;
  osg::Matrixd to_world;
  void operator()(const osg::Vec3& a, const osg::Vec3& b, const osg::Vec3& c) {
    out->push_back(osg::Vec3d(a) * to_world);
    out->push_back(osg::Vec3d(b) * to_world);
    out->push_back(osg::Vec3d(c) * to_world);
  }
};

// Every triangle of a loaded model, in world space, in its own winding.
class TriangleCollector : public osg::NodeVisitor {
 public:
  TriangleCollector() : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN) {}
  std::vector<osg::Vec3d> corners;
  void apply(osg::Drawable& drawable) override {
    osg::TriangleFunctor<CollectTriangle> f;
    f.out = &corners;
    f.to_world = osg::computeLocalToWorld(getNodePath());
    drawable.accept(f);
  }
};

// The drawn geometry: one vertex per face corner, white, or black where the face is turned away.
osg::ref_ptr<osg::Geode> coloured_geometry(const std::vector<osg::Vec3d>& corners, const engines::Point& camera,
                                            const std::array<double, 4>& light) {
  osg::ref_ptr<osg::Vec3Array> vertices = new osg::Vec3Array;
  osg::ref_ptr<osg::Vec4Array> colours = new osg::Vec4Array;
  for (std::size_t i = 0; i + 2 < corners.size(); i += 3) {
    const auto p = [&](std::size_t k) { return engines::Point{corners[k].x(), corners[k].y(), corners[k].z()}; };
    const bool dark = engines::turned_away_from_light(p(i), p(i + 1), p(i + 2), camera, light);
    for (std::size_t k = i; k < i + 3; ++k) {
      vertices->push_back(osg::Vec3(corners[k]));
      colours->push_back(dark ? osg::Vec4(0, 0, 0, 1) : osg::Vec4(1, 1, 1, 1));
    }
  }
  osg::ref_ptr<osg::Geometry> g = new osg::Geometry;
  g->setVertexArray(vertices);
  g->setColorArray(colours, osg::Array::BIND_PER_VERTEX);
  g->addPrimitiveSet(new osg::DrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(vertices->size())));
  osg::ref_ptr<osg::Geode> geode = new osg::Geode;
  geode->addDrawable(g);
  return geode;
}

// Reads the frame back after the main camera has drawn (before any buffer swap).
struct ReadBack : osg::Camera::DrawCallback {
  int width = 0, height = 0;
  mutable engines::Frame frame;
  void operator()(osg::RenderInfo&) const override { frame = engines::read_frame(width, height); }
};

// OSG's OBJ plugin warns "Obj unable to find material ''" for every object of the pack (they carry no
// usemtl): that line says nothing here; every other message is passed on.
struct QuietMissingMaterials : osg::NotifyHandler {
  void notify(osg::NotifySeverity, const char* message) override {
    if (std::strstr(message, "unable to find material") == nullptr) std::fputs(message, stderr);
  }
};

enum class Variant { ShadowMap, SoftShadowMap, ShadowMapNoOffset };

// A ShadowMap technique whose render-to-texture camera can be read: osgShadow keeps it protected,
// and its view and projection after a frame are the matrices ShadowMap::cull fitted and drew the map
// with (its camera computes no near/far of its own). OSG's matrices are row-vector, so ptr()'s
// row-major order is the column-vector matrix's column-major order: candidate.json's.
class ShadowCameraReader {
 public:
  virtual ~ShadowCameraReader() = default;
  engines::Declaration::View drawn_view() const {
    engines::Declaration::View v;
    const osg::Camera& c = *shadow_camera();
    std::copy_n(c.getViewMatrix().ptr(), 16, v.view.begin());
    std::copy_n(c.getProjectionMatrix().ptr(), 16, v.projection.begin());
    return v;
  }

 protected:
  virtual const osg::Camera* shadow_camera() const = 0;
};

template <class Technique>
class ReadableShadowMap : public Technique, public ShadowCameraReader {
 protected:
  const osg::Camera* shadow_camera() const override { return this->_camera.get(); }
};

osg::ref_ptr<osgShadow::ShadowMap> make_technique(Variant variant) {
  const bool soft = variant == Variant::SoftShadowMap;
  osg::ref_ptr<osgShadow::ShadowMap> t;
  if (soft) {
    osg::ref_ptr<osgShadow::SoftShadowMap> s = new ReadableShadowMap<osgShadow::SoftShadowMap>;
    s->setSoftnessWidth(kSoftnessWidth);
    t = s;
  } else {
    t = new ReadableShadowMap<osgShadow::ShadowMap>;
  }
  t->setTextureSize(osg::Vec2s(kMapSize, kMapSize));
  t->setAmbientBias(osg::Vec2(0.0f, 1.0f));
  if (variant == Variant::ShadowMapNoOffset) t->setPolygonOffset(osg::Vec2(0.0f, 0.0f));
  return t;
}

// Renders each light's mask into out_dir; returns, per light, the matrices its map was drawn with.
std::vector<std::vector<engines::Declaration::View>> render_scene(const engines::PackScene& s, Variant variant,
                                                                  const std::filesystem::path& out_dir) {
  std::vector<std::vector<engines::Declaration::View>> drawn;
  const osg::ref_ptr<osgDB::Options> options = new osgDB::Options("noRotation generateFacetNormals");
  std::vector<std::vector<osg::Vec3d>> objects;
  for (const engines::PackObject& o : s.objects) {
    const osg::ref_ptr<osg::Node> model = osgDB::readRefNodeFile(o.obj.string(), options.get());
    if (!model) throw std::runtime_error("OpenSceneGraph cannot load " + o.obj.string());
    TriangleCollector collect;
    model->accept(collect);
    objects.push_back(std::move(collect.corners));
  }

  osg::ref_ptr<osg::GraphicsContext::Traits> traits = new osg::GraphicsContext::Traits;
  traits->readDISPLAY();  // the display xvfb-run gives us, not :0
  traits->width = s.width;
  traits->height = s.height;
  traits->red = traits->green = traits->blue = 8;
  traits->depth = 24;
  traits->doubleBuffer = true;
  traits->windowDecoration = false;
  osg::ref_ptr<osg::GraphicsContext> gc = osg::GraphicsContext::createGraphicsContext(traits.get());
  if (!gc) throw std::runtime_error("OpenSceneGraph: no graphics context (is there an X display?)");

  osgViewer::Viewer viewer;
  viewer.setThreadingModel(osgViewer::Viewer::SingleThreaded);
  viewer.setLightingMode(osg::View::NO_LIGHT);
  osg::Camera* camera = viewer.getCamera();
  camera->setGraphicsContext(gc.get());
  camera->setViewport(0, 0, s.width, s.height);
  camera->setDrawBuffer(GL_BACK);  // read back before the swap
  camera->setReadBuffer(GL_BACK);
  camera->setClearColor(osg::Vec4(0, 0, 1, 1));
  camera->setComputeNearFarMode(osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR);
  camera->setViewMatrix(to_osg(s.view));
  camera->setProjectionMatrix(to_osg(s.projection_finite));
  osg::ref_ptr<ReadBack> read_back = new ReadBack;
  read_back->width = s.width;
  read_back->height = s.height;
  camera->setFinalDrawCallback(read_back.get());

  const engines::Point eye{s.camera_position[0], s.camera_position[1], s.camera_position[2]};
  for (const engines::PackLight& light : s.lights) {
    osg::ref_ptr<osgShadow::ShadowedScene> shadowed = new osgShadow::ShadowedScene(make_technique(variant));
    shadowed->getOrCreateStateSet()->setMode(GL_LIGHTING, osg::StateAttribute::OFF);
    osg::ref_ptr<osg::LightSource> source = new osg::LightSource;
    const std::array<double, 4>& h = light.homogeneous;
    source->getLight()->setLightNum(0);
    source->getLight()->setPosition(osg::Vec4(static_cast<float>(h[0]), static_cast<float>(h[1]),
                                              static_cast<float>(h[2]), static_cast<float>(h[3])));
    shadowed->addChild(source);
    static_cast<osgShadow::ShadowMap*>(shadowed->getShadowTechnique())->setLight(source.get());
    for (const std::vector<osg::Vec3d>& corners : objects) shadowed->addChild(coloured_geometry(corners, eye, h));
    viewer.setSceneData(shadowed);
    if (!viewer.isRealized()) viewer.realize();
    viewer.frame();
    if (read_back->frame.rgb.empty()) throw std::runtime_error("OpenSceneGraph drew no frame");
    engines::write_mask_png(out_dir / light.mask_file, s.width, s.height, engines::mask_from_frame(read_back->frame));
    read_back->frame = engines::Frame{};
    // One view for every light: ShadowMap draws a positional light's map as one perspective view too.
    drawn.push_back({dynamic_cast<const ShadowCameraReader&>(*shadowed->getShadowTechnique()).drawn_view()});
  }
  return drawn;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const engines::HarnessArgs args = engines::parse_harness_args(argc, argv);
    Variant variant = Variant::ShadowMap;
    if (args.variant == "softshadowmap") variant = Variant::SoftShadowMap;
    else if (args.variant == "shadowmap-no-offset") variant = Variant::ShadowMapNoOffset;
    else if (args.variant != "shadowmap")
      throw std::runtime_error("--variant must be shadowmap, softshadowmap or shadowmap-no-offset");
    const bool soft = variant == Variant::SoftShadowMap;
    osg::setNotifyLevel(osg::WARN);
    osg::setNotifyHandler(new QuietMissingMaterials);
    for (const std::string& name : engines::select_scenes(args.pack, args.scenes)) {
      const engines::PackScene s = engines::read_pack_scene(args.pack, name);
      const std::filesystem::path dir = args.out / name;
      std::filesystem::create_directories(dir);
      engines::Declaration d;
      d.light_matrices = render_scene(s, variant, dir);
      d.producer = "OpenSceneGraph";
      d.version = osgGetVersion();
      d.technique = soft ? "shadowmap-pcf" : "shadowmap";
      d.shadow_map_size = kMapSize;
      // The depth compare is bilinear (GL_LINEAR on the depth texture): its four texels lie within
      // half a texel beyond the nearest one. SoftShadowMap adds its jittered disk of
      // softness x map size texels around the point.
      d.filter_radius_texels = 0.5 + (soft ? static_cast<double>(kSoftnessWidth) * kMapSize : 0.0);
      // Its taps come from a 3D texture of random offsets indexed by the fragment's window position:
      // a kernel drawn at random per pixel, 64 taps (8 per axis) where the first 8 disagree.
      if (soft) d.light_taps = kSoftTaps;
      // glPolygonOffset(-1, -1) pulls the stored back faces toward the light: less allowance than
      // none, and the contract has no negative bias, so 0 is the honest declaration.
      d.slope_bias_texels = 0;
      d.constant_bias = 0;
      d.light_views_from_pack = false;
      engines::write_candidate_json(dir, d);
      std::printf("osg %s: %s\n", args.variant.c_str(), name.c_str());
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "osg harness: %s\n", e.what());
    return 1;
  }
}
