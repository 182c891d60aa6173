// engines/irrlicht/irrlicht_harness.cpp — renders an exported pack with Irrlicht's stencil shadow
// volumes (IMeshSceneNode::addShadowVolumeSceneNode), the way an Irrlicht user would, and writes a
// candidate folder: <out>/<scene>/mask.png (mask_<i>.png per light, one render per light) and
// candidate.json. --variant zfail (Irrlicht's default) or zpass; with the suffix -face-origins, the
// control run (below).
//
// How the pack becomes an Irrlicht scene (each a deliberate choice; engines/README.md says why):
//   * Meshes: Irrlicht's own OBJ loader. It mirrors x (x -> -x, Irrlicht is left-handed) and reverses
//     the winding, so the harness works in that mirrored world: camera and lights are mirrored too.
//   * Camera: the pack's gl view and projection, unchanged on the screen. Irrlicht has no
//     setViewMatrix; its camera builds a look-at, then multiplies the affector in. The camera stands
//     at the (mirrored) pack position looking along +z, which makes the look-at a pure translation,
//     and the affector supplies the rest: view = lookAt · affector = packView · mirrorX.
//   * Far plane: Irrlicht's z-fail volumes are finite (extruded by `infinity`) and it skips any volume
//     whose back cap lies beyond the camera's far plane (CShadowVolumeSceneNode::render), as its
//     documentation of addShadowVolumeSceneNode demands. The harness uses the pack's finite
//     projection with the far plane moved out far enough for that; near, field of view and aspect
//     are the pack's, so no pixel moves.
//   * Lights: Irrlicht reads only SLight::Position. A point (spot, rect: their centre) light is that
//     point; a directional light is a point 10^4 scene diagonals away along its direction.
//   * Materials: unlit, vertex colours, two-sided. Faces turned away from the light are painted
//     black by the harness (attached_shadow.hpp); all else white. The shadow colour is opaque black.
//   * The shadow volume is built by Irrlicht from the loaded mesh, untouched; the drawn mesh is a copy
//     with one vertex per face corner, so that faces can have their own colour.
//   * The control (-face-origins): every face becomes its own node, placed at its first vertex, with
//     the face as its shadow mesh. Irrlicht classifies faces with the light's position in the node's
//     space (CShadowVolumeSceneNode::createEdgesAndCaps); at a node placed on the face that position
//     is the direction from the face to the light, which is what the test needs. Each face then gets
//     its own volume (its three edges are open, so all three are extruded). Nothing else changes, so where this passes
//     and the plain run fails, the failure is Irrlicht's face classification, not this harness.
#include <GL/gl.h>
#include <irrlicht.h>

#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <string>
#include <vector>

#include "attached_shadow.hpp"
#include "harness_args.hpp"
#include "mask_output.hpp"
#include "pack_scene.hpp"

namespace {

using namespace irr;
using engines::Mat4;

// Irrlicht's world is the pack's mirrored in x (its OBJ loader's change of handedness).
core::vector3df to_irr(double x, double y, double z) {
  return {static_cast<f32>(-x), static_cast<f32>(y), static_cast<f32>(z)};
}
engines::Point to_point(const core::vector3df& v) { return {v.X, v.Y, v.Z}; }

// Irrlicht's matrix4 stores M[column * 4 + row] of the column-vector matrix (it hands pointer()
// straight to glLoadMatrixf), i.e. the D3DX layout.
core::matrix4 to_irr(const Mat4& m) {
  core::matrix4 out;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out[static_cast<u32>(c * 4 + r)] = static_cast<f32>(m[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)]);
  return out;
}

struct Bounds {
  core::vector3df lo{std::numeric_limits<f32>::max()}, hi{-std::numeric_limits<f32>::max()};
  void add(const core::vector3df& p) {
    lo.set(std::min(lo.X, p.X), std::min(lo.Y, p.Y), std::min(lo.Z, p.Z));
    hi.set(std::max(hi.X, p.X), std::max(hi.Y, p.Y), std::max(hi.Z, p.Z));
  }
  double diagonal() const { return static_cast<double>((hi - lo).getLength()); }
  core::vector3df centre() const { return (lo + hi) * 0.5f; }
};

// The drawn copy of `mesh`: one vertex per face corner, white, or black where the face is turned
// away from `light` (both in Irrlicht's world).
scene::SMesh* coloured_copy(const scene::IMesh* mesh, const engines::Point& camera, const std::array<double, 4>& light) {
  scene::SMesh* out = new scene::SMesh();
  scene::SMeshBuffer* buf = nullptr;
  for (u32 b = 0; b < mesh->getMeshBufferCount(); ++b) {
    const scene::IMeshBuffer* in = mesh->getMeshBuffer(b);
    const u16* idx = in->getIndices();
    for (u32 t = 0; t + 2 < in->getIndexCount(); t += 3) {
      if (!buf || buf->Vertices.size() + 3 > 65535) {  // 16-bit indices
        if (buf) {
          out->addMeshBuffer(buf);
          buf->drop();
        }
        buf = new scene::SMeshBuffer();
        buf->Material.Lighting = false;
        buf->Material.BackfaceCulling = false;
      }
      const core::vector3df p[3] = {in->getPosition(idx[t]), in->getPosition(idx[t + 1]), in->getPosition(idx[t + 2])};
      const bool dark = engines::turned_away_from_light(to_point(p[0]), to_point(p[1]), to_point(p[2]), camera, light);
      const video::SColor colour = dark ? video::SColor(255, 0, 0, 0) : video::SColor(255, 255, 255, 255);
      for (const core::vector3df& v : p) {
        buf->Indices.push_back(static_cast<u16>(buf->Vertices.size()));
        buf->Vertices.push_back(video::S3DVertex(v, core::vector3df(0, 1, 0), colour, core::vector2df(0, 0)));
      }
    }
  }
  if (buf) {
    buf->recalculateBoundingBox();
    out->addMeshBuffer(buf);
    buf->drop();
  }
  out->recalculateBoundingBox();
  return out;
}

// The pack's finite gl projection with its far plane moved to `far` (only the depth row changes).
Mat4 with_far(Mat4 p, double near, double far) {
  p[2][2] = -(far + near) / (far - near);
  p[2][3] = -2.0 * far * near / (far - near);
  return p;
}

// The control's nodes: one per face of `mesh`, at the face's first vertex, drawn in its colour and
// casting through its own shadow volume.
void add_face_nodes(scene::ISceneManager* smgr, const scene::IMesh* mesh, const engines::Point& camera,
                    const std::array<double, 4>& light, bool zfail, f32 infinity) {
  for (u32 b = 0; b < mesh->getMeshBufferCount(); ++b) {
    const scene::IMeshBuffer* in = mesh->getMeshBuffer(b);
    const u16* idx = in->getIndices();
    for (u32 t = 0; t + 2 < in->getIndexCount(); t += 3) {
      const core::vector3df p[3] = {in->getPosition(idx[t]), in->getPosition(idx[t + 1]), in->getPosition(idx[t + 2])};
      const bool dark = engines::turned_away_from_light(to_point(p[0]), to_point(p[1]), to_point(p[2]), camera, light);
      scene::SMeshBuffer* buf = new scene::SMeshBuffer();
      buf->Material.Lighting = false;
      buf->Material.BackfaceCulling = false;
      for (u16 k = 0; k < 3; ++k) {
        buf->Vertices.push_back(video::S3DVertex(p[k] - p[0], core::vector3df(0, 1, 0),
                                                 dark ? video::SColor(255, 0, 0, 0) : video::SColor(255, 255, 255, 255),
                                                 core::vector2df(0, 0)));
        buf->Indices.push_back(k);
      }
      buf->recalculateBoundingBox();
      scene::SMesh* face = new scene::SMesh();
      face->addMeshBuffer(buf);
      buf->drop();
      face->recalculateBoundingBox();
      scene::IMeshSceneNode* node = smgr->addMeshSceneNode(face, nullptr, -1, p[0]);
      node->setAutomaticCulling(scene::EAC_OFF);
      node->addShadowVolumeSceneNode(face, -1, zfail, infinity);
      face->drop();
    }
  }
}

void render_scene(const engines::PackScene& s, bool zfail, bool face_origins, const std::filesystem::path& out_dir,
                  std::string& version) {
  SIrrlichtCreationParameters params;
  params.DriverType = video::EDT_OPENGL;
  params.WindowSize = core::dimension2d<u32>(static_cast<u32>(s.width), static_cast<u32>(s.height));
  params.Bits = 24;
  params.ZBufferBits = 24;
  params.Stencilbuffer = true;
  params.AntiAlias = 0;
  params.Vsync = false;
  params.LoggingLevel = ELL_ERROR;
  IrrlichtDevice* device = createDeviceEx(params);
  if (!device) throw std::runtime_error("Irrlicht: no OpenGL device (is there an X display with a stencil buffer?)");
  version = device->getVersion();
  video::IVideoDriver* driver = device->getVideoDriver();
  scene::ISceneManager* smgr = device->getSceneManager();
  smgr->setShadowColor(video::SColor(255, 0, 0, 0));

  std::vector<scene::IMesh*> meshes;
  Bounds bounds;
  for (const engines::PackObject& o : s.objects) {
    scene::IAnimatedMesh* am = smgr->getMesh(o.obj.string().c_str());
    if (!am) throw std::runtime_error("Irrlicht cannot load " + o.obj.string());
    scene::IMesh* m = am->getMesh(0);
    for (u32 b = 0; b < m->getMeshBufferCount(); ++b)
      for (u32 v = 0; v < m->getMeshBuffer(b)->getVertexCount(); ++v) bounds.add(m->getMeshBuffer(b)->getPosition(v));
    meshes.push_back(m);
  }
  const double diagonal = bounds.diagonal();
  const core::vector3df camera = to_irr(s.camera_position[0], s.camera_position[1], s.camera_position[2]);

  // Volumes reach 1.5 scene diagonals past every caster vertex: past every receiver. Their back caps
  // then lie within that distance of the scene's box; the far plane goes beyond the farthest corner
  // such a cap's bounding box can have (never nearer than the pack's own far plane).
  const f32 infinity = static_cast<f32>(1.5 * diagonal);
  const double reach = static_cast<double>((camera - bounds.centre()).getLength()) + 0.5 * diagonal +
                       std::sqrt(3.0) * static_cast<double>(infinity);
  const double pack_far = s.projection_finite[2][3] / (s.projection_finite[2][2] + 1.0);
  const double far = std::max(pack_far, 1.01 * reach);
  const Mat4 projection = with_far(s.projection_finite, s.near, far);
  const Mat4 mirror_x{{{-1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}};
  const Mat4 to_camera{{{1, 0, 0, static_cast<double>(camera.X)},
                        {0, 1, 0, static_cast<double>(camera.Y)},
                        {0, 0, 1, static_cast<double>(camera.Z)},
                        {0, 0, 0, 1}}};
  const Mat4 affector = engines::multiply(to_camera, engines::multiply(s.view, mirror_x));

  for (std::size_t li = 0; li < s.lights.size(); ++li) {
    const engines::PackLight& light = s.lights[li];
    smgr->clear();
    // The light in Irrlicht's world: the point it reads, and the homogeneous light the harness's
    // attached-shadow colouring uses (a directional light stays a direction there).
    core::vector3df light_pos;
    std::array<double, 4> l_irr{};
    if (light.homogeneous[3] != 0) {
      const double w = light.homogeneous[3];
      light_pos = to_irr(light.homogeneous[0] / w, light.homogeneous[1] / w, light.homogeneous[2] / w);
      l_irr = {light_pos.X, light_pos.Y, light_pos.Z, 1.0};
    } else {
      core::vector3df dir = to_irr(light.homogeneous[0], light.homogeneous[1], light.homogeneous[2]);
      dir.normalize();
      light_pos = bounds.centre() + dir * static_cast<f32>(1e4 * diagonal);
      l_irr = {dir.X, dir.Y, dir.Z, 0.0};
    }

    for (scene::IMesh* m : meshes) {
      if (face_origins) {
        add_face_nodes(smgr, m, to_point(camera), l_irr, zfail, infinity);
        continue;
      }
      scene::SMesh* drawn = coloured_copy(m, to_point(camera), l_irr);
      scene::IMeshSceneNode* node = smgr->addMeshSceneNode(drawn);
      drawn->drop();
      node->setAutomaticCulling(scene::EAC_OFF);
      node->addShadowVolumeSceneNode(m, -1, zfail, infinity);
    }
    // Irrlicht only builds volumes for lights within twice their radius of the node.
    const f32 radius = static_cast<f32>(2.0 * static_cast<double>((light_pos - bounds.centre()).getLength()) + diagonal);
    scene::ILightSceneNode* l = smgr->addLightSceneNode(nullptr, light_pos, video::SColorf(1, 1, 1), radius);
    l->getLightData().CastShadows = true;
    scene::ICameraSceneNode* cam = smgr->addCameraSceneNode(nullptr, camera, camera + core::vector3df(0, 0, 1));
    cam->setUpVector(core::vector3df(0, 1, 0));
    cam->setProjectionMatrix(to_irr(projection));
    cam->setViewMatrixAffector(to_irr(affector));

    if (!device->run()) throw std::runtime_error("Irrlicht device closed");
    driver->beginScene(true, true, video::SColor(255, 0, 0, 255));
    // Irrlicht clears the stencil only after drawing a shadow; the first frame's is undefined.
    glClearStencil(0);
    glClear(GL_STENCIL_BUFFER_BIT);
    smgr->drawAll();
    const engines::Frame frame = engines::read_frame(s.width, s.height);
    driver->endScene();
    engines::write_mask_png(out_dir / light.mask_file, s.width, s.height, engines::mask_from_frame(frame));
  }
  device->closeDevice();
  device->run();
  device->drop();
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const engines::HarnessArgs args = engines::parse_harness_args(argc, argv);
    const std::string suffix = "-face-origins";
    const bool face_origins = args.variant.size() > suffix.size() && args.variant.compare(args.variant.size() - suffix.size(), suffix.size(), suffix) == 0;
    const std::string method = face_origins ? args.variant.substr(0, args.variant.size() - suffix.size()) : args.variant;
    if (method != "zfail" && method != "zpass")
      throw std::runtime_error("--variant must be zfail or zpass, optionally with the suffix -face-origins");
    const bool zfail = method == "zfail";
    for (const std::string& name : engines::select_scenes(args.pack, args.scenes)) {
      const engines::PackScene s = engines::read_pack_scene(args.pack, name);
      const std::filesystem::path dir = args.out / name;
      std::filesystem::create_directories(dir);
      std::string version;
      render_scene(s, zfail, face_origins, dir, version);
      engines::Declaration d;
      d.producer = "Irrlicht";
      d.version = version;
      d.technique = zfail ? "volume-zfail" : "volume-zpass";
      engines::write_candidate_json(dir, d);
      std::printf("irrlicht %s: %s\n", args.variant.c_str(), name.c_str());
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "irrlicht harness: %s\n", e.what());
    return 1;
  }
}
