// skin.cpp — a skinned vertex posed (skin.hpp): glTF 2.0's linear blend skinning, in double.
#include "shadowref/scene/skin.hpp"

namespace shadowref::scene {

Vec3<double> pose_vertex(const Skin& skin, std::size_t i) {
  const Eigen::Vector4d p(static_cast<double>(skin.bind_positions[i].x()), static_cast<double>(skin.bind_positions[i].y()),
                          static_cast<double>(skin.bind_positions[i].z()), 1.0);
  Eigen::Vector4d sum = Eigen::Vector4d::Zero();
  for (std::size_t k = 0; k < 4; ++k) {
    const double w = static_cast<double>(skin.weights[i][k]);
    if (w == 0) continue;
    sum += w * (skin.joints[skin.joint_indices[i][k]].world_from_bind() * p);
  }
  return sum.head<3>();
}

}  // namespace shadowref::scene
