// gltf_skin.cpp — a glTF file's pose (gltf_model.hpp): the first animation sampled at one time
// (glTF 2.0 §3.11 "Animations", Appendix C "Interpolation"), global node transforms, and skins read
// into one shadowref::scene::Skin (skin.hpp; glTF 2.0 §3.7.3 "Skins"). Every index and range of the
// file is checked before it is touched; every refusal is a MeshFileError.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "gltf_model.hpp"

namespace shadowref::scene {

namespace detail {
namespace {

std::string node_name(const tinygltf::Model& model, int n) {
  const std::string& name = model.nodes[static_cast<std::size_t>(n)].name;
  return "node " + std::to_string(n) + (name.empty() ? "" : " '" + name + "'");
}

std::vector<float> floats(const tinygltf::Model& model, int accessor, int components, const std::string& what) {
  int got = 0;
  return read_float_attribute(model, accessor, components, 0, what, got);
}

// One channel's value at `time`: `comps` doubles.
std::vector<double> sample(const std::vector<float>& times, const std::vector<float>& values, int comps,
                           const std::string& interpolation, double time, bool rotation) {
  const std::size_t n = times.size();
  const auto value = [&](std::size_t key, std::size_t part) {  // part: 0 in-tangent, 1 value, 2 out-tangent (CUBICSPLINE)
    const std::size_t base = interpolation == "CUBICSPLINE" ? (3 * key + part) * static_cast<std::size_t>(comps)
                                                              : key * static_cast<std::size_t>(comps);
    std::vector<double> v(static_cast<std::size_t>(comps));
    for (int c = 0; c < comps; ++c) v[static_cast<std::size_t>(c)] = static_cast<double>(values[base + static_cast<std::size_t>(c)]);
    return v;
  };
  if (time <= static_cast<double>(times.front())) return value(0, 1);
  if (time >= static_cast<double>(times.back())) return value(n - 1, 1);
  const std::size_t k = static_cast<std::size_t>(std::upper_bound(times.begin(), times.end(), time,
                                                                  [](double t, float key) { return t < static_cast<double>(key); }) -
                                                 times.begin()) - 1;
  const double t0 = static_cast<double>(times[k]), t1 = static_cast<double>(times[k + 1]);
  const double td = t1 - t0, s = (time - t0) / td;
  if (interpolation == "STEP") return value(k, 1);
  std::vector<double> out(static_cast<std::size_t>(comps));
  if (interpolation == "CUBICSPLINE") {
    const std::vector<double> v0 = value(k, 1), b0 = value(k, 2), a1 = value(k + 1, 0), v1 = value(k + 1, 1);
    const double s2 = s * s, s3 = s2 * s;
    for (std::size_t c = 0; c < out.size(); ++c)
      out[c] = (2 * s3 - 3 * s2 + 1) * v0[c] + td * (s3 - 2 * s2 + s) * b0[c] + (-2 * s3 + 3 * s2) * v1[c] + td * (s3 - s2) * a1[c];
  } else if (rotation) {  // LINEAR rotations: spherical linear interpolation (the shorter way, as Eigen's slerp)
    const std::vector<double> q0 = value(k, 1), q1 = value(k + 1, 1);
    const Eigen::Quaterniond a(q0[3], q0[0], q0[1], q0[2]), b(q1[3], q1[0], q1[1], q1[2]);
    const Eigen::Quaterniond q = a.normalized().slerp(s, b.normalized());
    return {q.x(), q.y(), q.z(), q.w()};
  } else {
    const std::vector<double> v0 = value(k, 1), v1 = value(k + 1, 1);
    for (std::size_t c = 0; c < out.size(); ++c) out[c] = v0[c] + s * (v1[c] - v0[c]);
  }
  return out;
}

}  // namespace

double pose_time(const tinygltf::Model& model) {
  if (model.animations.empty()) return 0;
  const tinygltf::Value& x = model.animations.front().extras;
  if (!x.IsObject() || !x.Has("pose_time")) return 0;
  const tinygltf::Value& t = x.Get("pose_time");
  if (!t.IsNumber()) throw MeshFileError("animations[0].extras.pose_time must be a number (seconds)");
  const double v = t.GetNumberAsDouble();
  if (!(v >= 0) || !std::isfinite(v)) throw MeshFileError("animations[0].extras.pose_time must be finite and >= 0");
  return v;
}

std::vector<Eigen::Matrix4d> posed_local_transforms(const tinygltf::Model& model, double time) {
  struct Trs {
    Eigen::Vector3d t = Eigen::Vector3d::Zero();
    Eigen::Quaterniond r = Eigen::Quaterniond::Identity();
    Eigen::Vector3d s = Eigen::Vector3d::Ones();
    bool animated = false;
  };
  std::vector<Trs> trs(model.nodes.size());
  for (std::size_t i = 0; i < model.nodes.size(); ++i) {
    const tinygltf::Node& n = model.nodes[i];
    if (n.translation.size() == 3) trs[i].t = Eigen::Vector3d(n.translation[0], n.translation[1], n.translation[2]);
    if (n.rotation.size() == 4) trs[i].r = Eigen::Quaterniond(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);
    if (n.scale.size() == 3) trs[i].s = Eigen::Vector3d(n.scale[0], n.scale[1], n.scale[2]);
  }
  if (!model.animations.empty()) {
    const tinygltf::Animation& anim = model.animations.front();
    for (std::size_t c = 0; c < anim.channels.size(); ++c) {
      const tinygltf::AnimationChannel& ch = anim.channels[c];
      const std::string where = "animations[0].channels[" + std::to_string(c) + "]";
      if (ch.target_node < 0) continue;  // glTF: a channel without a node is for an extension; nothing to pose
      if (static_cast<std::size_t>(ch.target_node) >= model.nodes.size())
        throw MeshFileError(where + ": node " + std::to_string(ch.target_node) + " does not exist");
      if (ch.target_path == "weights")
        throw MeshFileError(where + " animates morph target weights, which are not read (the shape would be silently wrong)");
      const bool rotation = ch.target_path == "rotation";
      if (ch.target_path != "translation" && ch.target_path != "scale" && !rotation)
        throw MeshFileError(where + ": unknown target path '" + ch.target_path + "'");
      Trs& node = trs[static_cast<std::size_t>(ch.target_node)];
      if (model.nodes[static_cast<std::size_t>(ch.target_node)].matrix.size() == 16)
        throw MeshFileError(where + " animates " + node_name(model, ch.target_node) + ", which has a matrix (glTF forbids it)");
      if (ch.sampler < 0 || static_cast<std::size_t>(ch.sampler) >= anim.samplers.size())
        throw MeshFileError(where + ": sampler " + std::to_string(ch.sampler) + " does not exist");
      const tinygltf::AnimationSampler& smp = anim.samplers[static_cast<std::size_t>(ch.sampler)];
      const std::string interp = smp.interpolation.empty() ? "LINEAR" : smp.interpolation;
      if (interp != "LINEAR" && interp != "STEP" && interp != "CUBICSPLINE")
        throw MeshFileError(where + ": unknown interpolation '" + interp + "'");
      const std::vector<float> times = floats(model, smp.input, 1, where + ": the sampler's input");
      if (times.empty()) throw MeshFileError(where + ": the sampler has no keyframes");
      for (std::size_t k = 1; k < times.size(); ++k)
        if (!(times[k] > times[k - 1])) throw MeshFileError(where + ": the sampler's input times must increase strictly");
      const int comps = rotation ? 4 : 3;
      const std::vector<float> values = floats(model, smp.output, comps, where + ": the sampler's output (" + ch.target_path + ")");
      const std::size_t per_key = interp == "CUBICSPLINE" ? 3 : 1;
      if (values.size() != times.size() * per_key * static_cast<std::size_t>(comps))
        throw MeshFileError(where + ": the sampler's output has " + std::to_string(values.size() / static_cast<std::size_t>(comps)) +
                            " elements for " + std::to_string(times.size()) + " keyframes (" + interp + ")");
      const std::vector<double> v = sample(times, values, comps, interp, time, rotation);
      if (rotation) node.r = Eigen::Quaterniond(v[3], v[0], v[1], v[2]);
      else if (ch.target_path == "translation") node.t = Eigen::Vector3d(v[0], v[1], v[2]);
      else node.s = Eigen::Vector3d(v[0], v[1], v[2]);
      node.animated = true;
    }
  }
  std::vector<Eigen::Matrix4d> locals(model.nodes.size());
  for (std::size_t i = 0; i < model.nodes.size(); ++i) {
    if (!trs[i].animated) {
      locals[i] = node_transform(model.nodes[i]);
      continue;
    }
    if (!(trs[i].r.norm() > 0)) throw MeshFileError(node_name(model, static_cast<int>(i)) + ": its animated rotation is zero");
    Eigen::Affine3d a = Eigen::Affine3d::Identity();
    a.translate(trs[i].t);
    a.rotate(trs[i].r.normalized());
    a.scale(trs[i].s);
    locals[i] = a.matrix();
    if (!locals[i].allFinite()) throw MeshFileError(node_name(model, static_cast<int>(i)) + ": its animated transform is not finite");
  }
  return locals;
}

std::vector<Eigen::Matrix4d> global_transforms(const tinygltf::Model& model, const std::vector<Eigen::Matrix4d>& locals) {
  const std::size_t n = model.nodes.size();
  std::vector<int> parent(n, -1);
  for (std::size_t i = 0; i < n; ++i)
    for (const int c : model.nodes[i].children) {
      if (c < 0 || static_cast<std::size_t>(c) >= n) throw MeshFileError("node " + std::to_string(c) + " does not exist");
      if (parent[static_cast<std::size_t>(c)] < 0) parent[static_cast<std::size_t>(c)] = static_cast<int>(i);
    }
  std::vector<Eigen::Matrix4d> globals(n);
  std::vector<bool> done(n, false);
  for (std::size_t i = 0; i < n; ++i) {
    // The chain up to a root or a node already done, then down it.
    std::vector<std::size_t> chain;
    for (std::size_t k = i; !done[k]; k = static_cast<std::size_t>(parent[k])) {
      chain.push_back(k);
      if (chain.size() > 65) throw MeshFileError("the node hierarchy is deeper than 64 (a cycle?)");
      if (parent[k] < 0) break;
    }
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
      const int p = parent[*it];
      globals[*it] = p < 0 ? locals[*it] : Eigen::Matrix4d(globals[static_cast<std::size_t>(p)] * locals[*it]);
      done[*it] = true;
    }
  }
  return globals;
}

std::size_t SkinBuilder::add_joint(const Skin::Joint& joint) {
  if (skin_.joints.size() >= kMaxSkinJoints)
    throw MeshFileError("more than " + std::to_string(kMaxSkinJoints) + " joints (skins' joints and rigid parts beside them)");
  if (!joint.world.allFinite() || !joint.inverse_bind.allFinite()) throw MeshFileError("a joint's matrix is not finite");
  skin_.joints.push_back(joint);
  return skin_.joints.size() - 1;
}

std::vector<Vec3<double>> SkinBuilder::add_rigid(const tinygltf::Primitive& prim, const Eigen::Matrix4d& xf) {
  const std::vector<Vec3<double>> bind = primitive_positions(model_, prim, Eigen::Matrix4d::Identity());
  const std::size_t joint = add_joint({xf, Eigen::Matrix4d::Identity()});
  for (const auto& p : bind) {
    skin_.bind_positions.push_back(p.cast<float>());
    skin_.joint_indices.push_back({static_cast<std::uint16_t>(joint), 0, 0, 0});
    skin_.weights.push_back({1.0f, 0.0f, 0.0f, 0.0f});
  }
  return primitive_positions(model_, prim, xf);
}

std::vector<Vec3<double>> SkinBuilder::add_skinned(const tinygltf::Primitive& prim, int skin_index) {
  if (skin_index < 0 || static_cast<std::size_t>(skin_index) >= model_.skins.size())
    throw MeshFileError("skin " + std::to_string(skin_index) + " does not exist");
  const tinygltf::Skin& skin = model_.skins[static_cast<std::size_t>(skin_index)];
  const std::string where = "skin " + std::to_string(skin_index);
  if (skin.joints.empty()) throw MeshFileError(where + " has no joints");
  // The skin's joints, once per skin.
  std::size_t offset = 0;
  const auto known = std::find_if(skin_offsets_.begin(), skin_offsets_.end(), [&](const auto& e) { return e.first == skin_index; });
  if (known != skin_offsets_.end()) {
    offset = known->second;
  } else {
    std::vector<float> ibm;
    if (skin.inverseBindMatrices >= 0) {
      const tinygltf::Accessor& acc = accessor_at(model_, skin.inverseBindMatrices);
      if (acc.type != TINYGLTF_TYPE_MAT4 || acc.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
        throw MeshFileError(where + ": inverseBindMatrices must be a float MAT4 accessor");
      if (acc.count < skin.joints.size())
        throw MeshFileError(where + ": inverseBindMatrices has " + std::to_string(acc.count) + " matrices for " +
                            std::to_string(skin.joints.size()) + " joints");
      const AccessorView v = view_accessor(model_, skin.inverseBindMatrices, 16 * sizeof(float));
      ibm.resize(16 * skin.joints.size());
      for (std::size_t j = 0; j < skin.joints.size(); ++j) std::memcpy(&ibm[16 * j], v.data + j * v.stride, 16 * sizeof(float));
    }
    offset = skin_.joints.size();
    for (std::size_t j = 0; j < skin.joints.size(); ++j) {
      const int node = skin.joints[j];
      if (node < 0 || static_cast<std::size_t>(node) >= model_.nodes.size())
        throw MeshFileError(where + ": joint " + std::to_string(j) + " is node " + std::to_string(node) + ", which does not exist");
      Skin::Joint joint;
      joint.world = globals_[static_cast<std::size_t>(node)];
      if (!ibm.empty())
        for (int c = 0; c < 4; ++c)
          for (int r = 0; r < 4; ++r) joint.inverse_bind(r, c) = static_cast<double>(ibm[16 * j + static_cast<std::size_t>(4 * c + r)]);
      if (!joint.inverse_bind.allFinite()) throw MeshFileError(where + ": inverse bind matrix " + std::to_string(j) + " is not finite");
      add_joint(joint);
    }
    skin_offsets_.emplace_back(skin_index, offset);
  }
  const std::vector<Vec3<double>> bind = primitive_positions(model_, prim, Eigen::Matrix4d::Identity());
  const auto joints_it = prim.attributes.find("JOINTS_0");
  const auto weights_it = prim.attributes.find("WEIGHTS_0");
  if (joints_it == prim.attributes.end() || weights_it == prim.attributes.end())
    throw MeshFileError("a primitive of a skinned mesh lacks JOINTS_0 or WEIGHTS_0");
  if (prim.attributes.count("JOINTS_1") || prim.attributes.count("WEIGHTS_1"))
    throw MeshFileError("JOINTS_1 / WEIGHTS_1 (more than four joints per vertex) are not read");
  const tinygltf::Accessor& jacc = accessor_at(model_, joints_it->second);
  const std::size_t jsize = jacc.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? 1
                            : jacc.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 2
                                                                                           : 0;
  if (jacc.type != TINYGLTF_TYPE_VEC4 || jsize == 0) throw MeshFileError("JOINTS_0 must be an unsigned byte or short VEC4 accessor");
  const AccessorView jv = view_accessor(model_, joints_it->second, 4 * jsize);
  int got = 0;
  const std::vector<float> w = read_float_attribute(model_, weights_it->second, 4, 0, "WEIGHTS_0", got);
  if (jv.count != bind.size() || w.size() != 4 * bind.size())
    throw MeshFileError("JOINTS_0 and WEIGHTS_0 must have one element per vertex (" + std::to_string(bind.size()) + ")");
  std::vector<Vec3<double>> posed;
  posed.reserve(bind.size());
  for (std::size_t i = 0; i < bind.size(); ++i) {
    std::array<std::uint16_t, 4> ids{};
    std::array<float, 4> ws{};
    float sum = 0;
    for (std::size_t k = 0; k < 4; ++k) {
      std::uint16_t id = 0;
      if (jsize == 1) id = jv.data[i * jv.stride + k];
      else std::memcpy(&id, jv.data + i * jv.stride + 2 * k, 2);
      ws[k] = w[4 * i + k];
      if (!(ws[k] >= 0)) throw MeshFileError("WEIGHTS_0 of vertex " + std::to_string(i) + " is negative");
      if (ws[k] > 0 && id >= skin.joints.size())
        throw MeshFileError("JOINTS_0 of vertex " + std::to_string(i) + " names joint " + std::to_string(id) + " of " +
                            std::to_string(skin.joints.size()));
      ids[k] = static_cast<std::uint16_t>(ws[k] > 0 ? offset + id : offset);  // an unweighted slot names a valid joint
      sum += ws[k];
    }
    if (!(sum > 0)) throw MeshFileError("WEIGHTS_0 of vertex " + std::to_string(i) + " are all 0");
    skin_.bind_positions.push_back(bind[i].cast<float>());
    skin_.joint_indices.push_back(ids);
    skin_.weights.push_back(ws);
    const Vec3<double> p = pose_vertex(skin_, skin_.bind_positions.size() - 1);
    if (!p.allFinite()) throw MeshFileError("vertex " + std::to_string(i) + " is posed to a non-finite position");
    posed.push_back(p);
  }
  return posed;
}

}  // namespace detail
}  // namespace shadowref::scene
