// shadowref/result.hpp — the value-or-reason type returned by every function that can fail.
//
// C++20 has no std::expected, so this is the smallest form of it: either a value, or an Error
// naming what was wrong with the input. Never holds a NaN that nobody asked for.
#pragma once

#include <cassert>
#include <optional>
#include <stdexcept>
#include <utility>

namespace shadowref {

// Why a math function refused its input. describe() gives the sentence a command line prints.
enum class Error {
  NonFinite,            // an input is NaN or infinite
  ZeroNormal,           // a plane's normal (a, b, c) has zero length
  CollinearPoints,      // three points do not span a plane
  ZeroLight,            // the homogeneous light (x, y, z, w) is all zeros
  LightOnPlane,         // P·L = 0: the shadow matrix would have rank 1
  NearNotPositive,      // near <= 0 for a perspective projection
  FarNotBeyondNear,     // far <= near
  ZeroAspect,           // aspect <= 0
  FovOutOfRange,        // fovy not in (0, pi)
  EmptyFrustum,         // left == right or bottom == top
  EpsilonOutOfRange,    // the infinite far plane's epsilon not in [0, 1)
  ReversedNeedsZeroToOne,  // reversed-Z is defined with the 0..1 depth range only
  EyeAtTarget,          // look_at with eye == target
  UpParallelToView,     // look_at with up parallel to the viewing direction
  EmptyMesh,            // a mesh without triangles
  IndexOutOfRange,      // a triangle names a vertex that does not exist
  MeshTooLarge,         // more vertices or triangles than the 32-bit index buffers can address
  NegativeLightW,       // a homogeneous light with w < 0 (facing would be reversed)
  LightOnCaster,        // the light coincides with a caster vertex: no extrusion direction there
  DistanceNotPositive,  // a finite extrusion distance <= 0
  SingularMatrix,       // a matrix that must be inverted is singular
  InvalidShape,         // a procedural shape's size or tessellation is out of range
  CascadeCountOutOfRange,  // a cascade count outside [1, kMaxCascades]
  SplitWeightOutOfRange,   // the practical split scheme's weight outside [0, 1]
};

constexpr const char* describe(Error e) {
  switch (e) {
    case Error::NonFinite: return "an input is NaN or infinite";
    case Error::ZeroNormal: return "the plane normal (a, b, c) has zero length";
    case Error::CollinearPoints: return "the three points are collinear (or coincide): they do not define a plane";
    case Error::ZeroLight: return "the light (x, y, z, w) is all zeros";
    case Error::LightOnPlane: return "the light lies on the plane (P.L = 0): the shadow matrix would be degenerate (rank 1)";
    case Error::NearNotPositive: return "near must be > 0";
    case Error::FarNotBeyondNear: return "far must be > near";
    case Error::ZeroAspect: return "aspect must be > 0";
    case Error::FovOutOfRange: return "fovy must be in (0, 180) degrees";
    case Error::EmptyFrustum: return "left must differ from right and bottom from top";
    case Error::EpsilonOutOfRange: return "epsilon must be in [0, 1)";
    case Error::ReversedNeedsZeroToOne: return "reversed-Z needs the zero-to-one depth range";
    case Error::EyeAtTarget: return "eye and target coincide";
    case Error::UpParallelToView: return "up is parallel to the viewing direction";
    case Error::EmptyMesh: return "the mesh has no triangles";
    case Error::IndexOutOfRange: return "a triangle index is out of range (no such vertex)";
    case Error::MeshTooLarge: return "the mesh is too large for 32-bit indices";
    case Error::NegativeLightW: return "the light's w must be >= 0 (w = 1 point light, w = 0 directional)";
    case Error::LightOnCaster: return "the light coincides with a caster vertex: the volume has no extrusion direction there";
    case Error::DistanceNotPositive: return "the extrusion distance must be > 0";
    case Error::SingularMatrix: return "the matrix is singular";
    case Error::InvalidShape: return "the shape's size or tessellation is out of range";
    case Error::CascadeCountOutOfRange: return "the cascade count must be in [1, 8]";
    case Error::SplitWeightOutOfRange: return "the split weight (lambda) must be in [0, 1]";
  }
  return "unknown error";
}

template <class T>
class [[nodiscard]] Result {
 public:
  Result(T value) : value_(std::move(value)) {}  // NOLINT: implicit on purpose, like expected
  Result(Error error) : error_(error) {}         // NOLINT

  bool ok() const { return value_.has_value(); }
  explicit operator bool() const { return ok(); }
  Error error() const {
    assert(!ok());
    return error_;
  }
  const char* message() const { return ok() ? "ok" : describe(error_); }

  // Access the value; throws std::logic_error when there is none (a programming error).
  const T& value() const& {
    if (!value_) throw std::logic_error(describe(error_));
    return *value_;
  }
  T&& value() && {
    if (!value_) throw std::logic_error(describe(error_));
    return std::move(*value_);
  }
  const T& operator*() const& { return value(); }
  const T* operator->() const { return &value(); }

 private:
  std::optional<T> value_;
  Error error_ = Error::NonFinite;
};

}  // namespace shadowref
