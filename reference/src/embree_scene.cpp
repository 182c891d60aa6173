// embree_scene.cpp — EmbreeScene: device, triangle geometries, commit.
#include "shadowref/reference/embree_scene.hpp"

#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

namespace shadowref::reference {
namespace {

void check(RTCDevice device, const char* what) {
  const RTCError err = rtcGetDeviceError(device);
  if (err != RTC_ERROR_NONE) throw EmbreeError(std::string("Embree: ") + what + " failed (error " + std::to_string(static_cast<int>(err)) + ")");
}

}  // namespace

EmbreeScene::EmbreeScene(const scene::Scene& scene) : source_(&scene) {
  device_ = rtcNewDevice(nullptr);
  if (!device_) throw EmbreeError("Embree: rtcNewDevice failed (error " + std::to_string(static_cast<int>(rtcGetDeviceError(nullptr))) + ")");
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
    rtcCommitGeometry(geom);
    rtcAttachGeometryByID(scene_, geom, static_cast<unsigned>(i));
    rtcReleaseGeometry(geom);
    check(device_, "attaching a geometry");
  }
  rtcCommitScene(scene_);
  check(device_, "building the BVH");
  const auto b = scene::bounds(scene);
  const double d = (b[1] - b[0]).norm();
  extent_ = d > 0 ? d : 1;
}

EmbreeScene::~EmbreeScene() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

}  // namespace shadowref::reference
