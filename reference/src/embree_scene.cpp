// embree_scene.cpp — EmbreeScene: device, triangle geometries, commit.
#include "shadowref/reference/embree_scene.hpp"

#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#include "shadowref/outputs/interruption.hpp"

namespace shadowref::reference {
namespace {

void check(RTCDevice device, const char* what) {
  const RTCError err = rtcGetDeviceError(device);
  if (err != RTC_ERROR_NONE) throw EmbreeError(std::string("Embree: ") + what + " failed (error " + std::to_string(static_cast<int>(err)) + ")");
}

// The alpha test of a masked object (scene/alpha_mask.hpp), as Embree's filter function: called for
// every candidate hit on that object's geometry (camera rays and shadow rays alike, in no particular
// order along the ray), it rejects a hit on a point below the cutoff (valid = 0), so the ray goes on
// through the card. Embree's u, v are the barycentrics of the triangle's vertices 1 and 2, the
// rule's own (alpha_opaque_at).
void alpha_filter(const RTCFilterFunctionNArguments* args) {
  const auto* object = static_cast<const scene::Object*>(args->geometryUserPtr);
  const scene::AlphaMask& mask = *object->alpha;
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const unsigned prim = RTCHitN_primID(args->hit, args->N, i);
    const float u = RTCHitN_u(args->hit, args->N, i), v = RTCHitN_v(args->hit, args->N, i);
    if (!scene::alpha_opaque_at(mask, object->mesh.triangles[prim], u, v)) args->valid[i] = 0;
  }
}

}  // namespace

bool cpu_runs_embree_kernel(std::string_view name) {
  __builtin_cpu_init();
  if (name == "sse2") return true;  // every x86-64 CPU
  if (name == "sse4.2") return __builtin_cpu_supports("sse4.2");
  if (name == "avx2") return __builtin_cpu_supports("avx2");
  if (name == "avx512")
    return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq") &&
           __builtin_cpu_supports("avx512vl");
  return false;
}

EmbreeScene::EmbreeScene(const scene::Scene& scene, const std::string& device_config) : source_(&scene) {
  device_ = rtcNewDevice(device_config.empty() ? nullptr : device_config.c_str());
  if (!device_)
    throw EmbreeError("Embree: rtcNewDevice(\"" + device_config + "\") failed (error " +
                      std::to_string(static_cast<int>(rtcGetDeviceError(nullptr))) + ")");
  // A constructor that throws runs no destructor: whatever stops the build (an Embree error, an
  // interruption) releases the scene and the device here, or their buffers leak.
  try {
    build(scene);
  } catch (...) {
    if (scene_) rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
    throw;
  }
  const auto b = scene::bounds(scene);
  const double d = (b[1] - b[0]).norm();
  extent_ = d > 0 ? d : 1;
}

void EmbreeScene::build(const scene::Scene& scene) {
  scene_ = rtcNewScene(device_);
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const auto& mesh = scene.objects[i].mesh;
    RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                          3 * sizeof(float), mesh.positions.size()));
    auto* t = static_cast<std::uint32_t*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                  3 * sizeof(std::uint32_t), mesh.triangles.size()));
    check(device_, "allocating a geometry buffer");
    for (std::size_t k = 0; k < mesh.positions.size(); ++k)
      for (int c = 0; c < 3; ++c) v[3 * k + static_cast<std::size_t>(c)] = mesh.positions[k][c];
    std::memcpy(t, mesh.triangles.data(), mesh.triangles.size() * sizeof(mesh.triangles[0]));
    // Only masked geometry gets the filters: every other hit costs nothing more (reference_bench).
    if (scene.objects[i].alpha) {
      // Embree takes a void*; the filter only reads the object, which outlives the BVH (source_).
      rtcSetGeometryUserData(geom, const_cast<scene::Object*>(&scene.objects[i]));
      rtcSetGeometryOccludedFilterFunction(geom, alpha_filter);
      rtcSetGeometryIntersectFilterFunction(geom, alpha_filter);
    }
    rtcCommitGeometry(geom);
    rtcAttachGeometryByID(scene_, geom, static_cast<unsigned>(i));
    rtcReleaseGeometry(geom);
    check(device_, "attaching a geometry");
  }
  // SIGINT / SIGTERM cancel a long BVH build (a large level's takes seconds): Embree asks this as it
  // builds, and a false answer ends the build, which is then the stop, not an Embree failure.
  rtcSetSceneProgressMonitorFunction(scene_, [](void*, double) { return !outputs::interrupt_signal(); }, nullptr);
  rtcCommitScene(scene_);
  outputs::throw_if_interrupted();
  check(device_, "building the BVH");
}

EmbreeScene::~EmbreeScene() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

}  // namespace shadowref::reference
