// generators.hpp — RapidCheck generators for the geometry of shadows, built on purpose.
//
// RapidCheck's floating-point generators never produce NaN, infinities, −0 or subnormals and have
// no ranges (docs/dependencies.md), so every scalar here comes from an INTEGER range mapped onto the wanted
// interval (or a power of ten for scales): the values are reproducible from the seed and shrink
// toward simple ones (0, the low end, scale 1). Geometry is generated in double and cast to the
// scalar under test by the property. Every case type prints itself (operator<<) so a shrunk
// counterexample can be read.
#pragma once

#include <rapidcheck.h>

#include <cmath>
#include <iomanip>
#include <numbers>
#include <ostream>
#include <vector>

#include <Eigen/Geometry>

#include "property_support.hpp"
#include "shadowref/conventions.hpp"

namespace shadowref::prop::gen {

// Grid resolution of the scalar generators: 2^20 steps per interval.
inline constexpr int kSteps = 1 << 20;

// A value in [−half, half] on a grid, shrinking toward 0.
inline rc::Gen<double> centered(double half) {
  return rc::gen::map(rc::gen::inRange(0, 2 * kSteps + 1), [half](int i) {
    const int k = (i % 2 == 0) ? i / 2 : -(i + 1) / 2;  // 0, −1, 1, −2, 2 …: shrinks to 0
    return half * static_cast<double>(k) / static_cast<double>(kSteps);
  });
}

// A value in [lo, hi] on a grid, shrinking toward lo.
inline rc::Gen<double> uniform(double lo, double hi) {
  return rc::gen::map(rc::gen::inRange(0, kSteps + 1),
                      [lo, hi](int i) { return lo + (hi - lo) * static_cast<double>(i) / static_cast<double>(kSteps); });
}

// 10^e with e uniform in [e_lo, e_hi] (log-uniform scales), shrinking toward 10^0 when 0 is inside.
inline rc::Gen<double> power_of_ten(double e_lo, double e_hi) {
  return rc::gen::map(uniform(0, 1), [e_lo, e_hi](double u) {
    const double e = (e_lo <= 0 && e_hi >= 0) ? (u < 0.5 ? -e_lo * (2 * u - 1) : e_hi * (2 * u - 1)) : e_lo + (e_hi - e_lo) * u;
    return std::pow(10.0, e);
  });
}

inline rc::Gen<Vec3<double>> vec3(double half) {
  return rc::gen::apply([](double x, double y, double z) { return Vec3<double>(x, y, z); }, centered(half),
                        centered(half), centered(half));
}

// A unit vector (rejection of the small ones keeps the direction well defined).
inline rc::Gen<Vec3<double>> direction() {
  return rc::gen::map(rc::gen::suchThat(vec3(1), [](const Vec3<double>& v) { return v.norm() > 0.25; }),
                      [](const Vec3<double>& v) { return Vec3<double>(v.normalized()); });
}

// Points over scales from 1e-3 to 1e4: a point of the unit cube times 10^e, e in [−3, 4].
inline rc::Gen<Vec3<double>> point() {
  return rc::gen::apply([](const Vec3<double>& v, double s) { return Vec3<double>(v * s); }, vec3(1), power_of_ten(-3, 4));
}

// ---- planes and lights -----------------------------------------------------------------------

// A plane through `origin` with unit `normal`, stored unnormalised as length · (n, −n·origin).
struct PlaneCase {
  Vec3<double> normal;  // unit
  Vec3<double> origin;  // a point on the plane
  double length = 1;    // |(a, b, c)|
  Vec4<double> abcd() const { return length * Vec4<double>(normal.x(), normal.y(), normal.z(), -normal.dot(origin)); }
  friend std::ostream& operator<<(std::ostream& os, const PlaneCase& p) {
    return os << "plane abcd=" << str(p.abcd()) << " (unit normal " << str(p.normal) << " through " << str(p.origin)
              << ", |n|=" << p.length << ")";
  }
};

// Planes, including nearly degenerate ones: normals within 1e-7 of an axis, tiny (1e-6) and huge
// (1e6) normal lengths, planes far from the origin (d up to 1e4 · |n|) and through it.
inline rc::Gen<PlaneCase> plane() {
  const auto normal = rc::gen::oneOf(
      direction(),
      rc::gen::apply(
          [](int axis, const Vec3<double>& tilt, double size) {
            Vec3<double> n = Vec3<double>::Unit(axis) + size * tilt;
            return Vec3<double>(n.normalized());
          },
          rc::gen::inRange(0, 3), vec3(1), power_of_ten(-7, -2)));
  const auto origin = rc::gen::oneOf(point(), rc::gen::just(Vec3<double>(Vec3<double>::Zero())));
  return rc::gen::construct<PlaneCase>(normal, origin, power_of_ten(-6, 6));
}

// A homogeneous light (w = 1 point, w = 0 directional toward xyz).
struct LightCase {
  Vec4<double> L;
  friend std::ostream& operator<<(std::ostream& os, const LightCase& l) {
    return os << (l.L.w() == 0 ? "directional light " : "point light ") << str(l.L);
  }
};

// A point light at height h over `plane` (either side), h from 1e-3 to 1e4 — or close to the
// plane: h from 1e-6 to 1e-3 of the scale of the light's position.
inline rc::Gen<LightCase> point_light(const PlaneCase& plane) {
  return rc::gen::apply(
      [plane](const Vec3<double>& lateral, double height, bool below, bool close) {
        const Vec3<double> foot = plane.origin + lateral - plane.normal * plane.normal.dot(lateral);
        const double scale = std::max(1.0, foot.cwiseAbs().maxCoeff());
        const double h = (close ? height * 1e-3 * scale : height) * (below ? -1 : 1);
        const Vec3<double> p = foot + h * plane.normal;
        return LightCase{Vec4<double>(p.x(), p.y(), p.z(), 1)};
      },
      point(), power_of_ten(-3, 4), rc::gen::arbitrary<bool>(), rc::gen::weightedOneOf<bool>({{4, rc::gen::just(false)}, {1, rc::gen::just(true)}}));
}

// A directional light making an angle with `plane` from grazing (sin = 1e-4) to perpendicular.
inline rc::Gen<LightCase> directional_light(const PlaneCase& plane) {
  return rc::gen::apply(
      [plane](const Vec3<double>& d, double sine, bool below) {
        Vec3<double> t = d - plane.normal * plane.normal.dot(d);
        if (t.norm() < 1e-3) t = plane.normal.unitOrthogonal();
        t.normalize();
        const double s = std::min(sine, 1.0);
        const Vec3<double> l = t * std::sqrt(1 - s * s) + plane.normal * (below ? -s : s);
        return LightCase{Vec4<double>(l.x(), l.y(), l.z(), 0)};
      },
      direction(), power_of_ten(-4, 0), rc::gen::arbitrary<bool>());
}

inline rc::Gen<LightCase> light(const PlaneCase& plane) {
  return rc::gen::weightedOneOf<LightCase>({{3, point_light(plane)}, {1, directional_light(plane)}});
}

// A point on `plane`, at lateral offsets over all scales.
inline rc::Gen<Vec3<double>> point_on(const PlaneCase& plane) {
  return rc::gen::map(point(), [plane](const Vec3<double>& v) {
    return Vec3<double>(plane.origin + v - plane.normal * plane.normal.dot(v));
  });
}

// ---- cameras -----------------------------------------------------------------------------------

// A well-posed camera: fovy 10..120 degrees, aspect 0.5..2.5, near 1e-2..10, far/near 10..1e6, eye
// over all scales looking at a target 1..100 away, up not within 5 degrees of the view direction.
struct CameraCase {
  double fovy_deg = 60, aspect = 1, near = 0.1, far_ratio = 1000;
  Vec3<double> eye, forward, up;
  double distance = 10;
  int convention = 0;  // index into the adapter's list
  double fovy() const { return fovy_deg * std::numbers::pi / 180; }
  double far() const { return near * far_ratio; }
  Vec3<double> target() const { return eye + distance * forward; }
  friend std::ostream& operator<<(std::ostream& os, const CameraCase& c) {
    return os << "camera fovy=" << c.fovy_deg << "deg aspect=" << c.aspect << " near=" << c.near << " far=" << c.far()
              << " eye=" << str(c.eye) << " target=" << str(c.target()) << " up=" << str(c.up)
              << " convention#" << c.convention;
  }
};

inline rc::Gen<CameraCase> camera(int conventions) {
  return rc::gen::apply(
      [](double fovy, double aspect, double near, double ratio, const Vec3<double>& eye, const Vec3<double>& fwd,
         const Vec3<double>& up, double dist, int conv) {
        return CameraCase{fovy, aspect, near, ratio, eye, fwd, up, dist, conv};
      },
      uniform(10, 120), uniform(0.5, 2.5), power_of_ten(-2, 1), power_of_ten(1, 6), point(), direction(),
      direction(), power_of_ten(0, 2), rc::gen::inRange(0, conventions))
      .as("camera");
}

inline bool well_posed(const CameraCase& c) {
  return std::abs(c.forward.dot(c.up)) < std::cos(5 * std::numbers::pi / 180);
}

// ---- view volumes (the clip-space x/y properties) ------------------------------------------------

// A perspective lens: the same ranges as CameraCase (fovy 10..120 degrees, aspect 0.5..2.5, near
// 1e-2..10, far/near 10..1e6), without the camera's placement.
struct LensCase {
  double fovy_deg = 60, aspect = 1, near = 0.1, far_ratio = 1000;
  double fovy() const { return fovy_deg * std::numbers::pi / 180; }
  double far() const { return near * far_ratio; }
  friend std::ostream& operator<<(std::ostream& os, const LensCase& c) {
    return os << "lens fovy=" << c.fovy_deg << "deg aspect=" << c.aspect << " near=" << c.near << " far=" << c.far();
  }
};

inline rc::Gen<LensCase> lens() {
  return rc::gen::construct<LensCase>(uniform(10, 120), uniform(0.5, 2.5), power_of_ten(-2, 1), power_of_ten(1, 6));
}

// An off-centre frustum: the near rectangle's centre (cx, cy) and half-extents (hx, hy) in units of
// near. Centres up to 2 near from the axis and half-extents from 0.05 to 3 near, so that many
// rectangles do not contain the view axis at all (tiles, stereo eyes, oblique portals).
struct FrustumCase {
  double cx = 0, cy = 0, hx = 1, hy = 1, near = 0.1, far_ratio = 1000;
  double l() const { return near * (cx - hx); }
  double r() const { return near * (cx + hx); }
  double b() const { return near * (cy - hy); }
  double t() const { return near * (cy + hy); }
  double far() const { return near * far_ratio; }
  friend std::ostream& operator<<(std::ostream& os, const FrustumCase& c) {
    return os << "frustum l=" << c.l() << " r=" << c.r() << " b=" << c.b() << " t=" << c.t() << " near=" << c.near
              << " far=" << c.far();
  }
};

inline rc::Gen<FrustumCase> off_centre_frustum() {
  return rc::gen::construct<FrustumCase>(centered(2), centered(2), power_of_ten(-1.3, 0.5), power_of_ten(-1.3, 0.5),
                                         power_of_ten(-2, 1), power_of_ten(1, 6));
}

// An orthographic box: a unit-sized case (centre in [−1, 1]², half-extents and depth 1e-2..1e2,
// near in [−1, 1], so ≤ 0 too) times a scale 1e-3..1e4. Every extent is at least 1e-2 of the box's
// distance from the origin, so r − l and far − near stay far from zero in float.
struct OrthoCase {
  double cx = 0, cy = 0, hx = 1, hy = 1, near = 0, depth = 1, scale = 1;
  double l() const { return scale * (cx - hx); }
  double r() const { return scale * (cx + hx); }
  double b() const { return scale * (cy - hy); }
  double t() const { return scale * (cy + hy); }
  double n() const { return scale * near; }
  double f() const { return scale * (near + depth); }
  friend std::ostream& operator<<(std::ostream& os, const OrthoCase& c) {
    return os << "ortho l=" << c.l() << " r=" << c.r() << " b=" << c.b() << " t=" << c.t() << " near=" << c.n()
              << " far=" << c.f();
  }
};

inline rc::Gen<OrthoCase> ortho_box() {
  return rc::gen::construct<OrthoCase>(centered(1), centered(1), power_of_ten(-2, 2), power_of_ten(-2, 2), centered(1),
                                       power_of_ten(-2, 2), power_of_ten(-3, 4));
}

}  // namespace shadowref::prop::gen
