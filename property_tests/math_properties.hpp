// math_properties.hpp — the laws of the planar shadow matrix and of projections (depth, and where
// clip space puts view-space x and y), as RapidCheck properties over an adapter (math_adapter.hpp). Each property is a function template on
// the scalar T; math_properties_test.cpp runs them all in float and double, and teeth_test.cpp
// runs the same functions on deliberately wrong adapters.
//
// Checks are evaluated in long double (Wide) from the T values the adapter returned, so only the
// adapter's own rounding is judged. Every tolerance is rounding<T>(ops, magnitude): the number of
// rounding steps the adapter's computation takes times the magnitude of the terms it summed —
// which is where the input's condition enters (a light close to the plane, a point projected far
// away, a far plane close to the near one).
#pragma once

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <optional>
#include <ostream>
#include <vector>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "generators.hpp"
#include "math_adapter.hpp"
#include "property_support.hpp"
#include "shadowref/projection.hpp"
#include "shadowref/view.hpp"

namespace shadowref::prop {

using W4 = Vec4<Wide>;
using WM = Mat4<Wide>;

// Rounding steps of the shadow matrix: normalising the plane (a 3-term sum of squares, a square
// root, a division: 6), P·L (a 4-term sum: 4), one product and one subtraction per entry (2); 16
// leaves the factor of 4/3 that reordered sums (SIMD) may take.
inline constexpr Wide kShadowMatrixOps = 16;

// The case a shadow-matrix property runs on: the inputs as the scalar T sees them, and the plane
// normalised in Wide (the contract's P).
template <class T>
struct ShadowInputs {
  Vec4<T> plane, light;
  W4 P, L;           // normalised plane, light, in Wide
  Wide PL = 0;       // P·L
  Wide sigma = 0;    // Σ|P_i L_i|: the magnitude P·L is summed from
  // Entry-wise bound A_ij = δ_ij σ + |L_i| |P_j| of |S| and of the terms each entry is made of.
  WM A() const {
    WM a = L.cwiseAbs() * P.cwiseAbs().transpose();
    a.diagonal().array() += sigma;
    return a;
  }
};

template <class T>
ShadowInputs<T> shadow_inputs(const Vec4<double>& plane, const Vec4<double>& light) {
  ShadowInputs<T> in;
  in.plane = plane.cast<T>();
  in.light = light.cast<T>();
  const W4 p = in.plane.template cast<Wide>();
  in.P = p / p.template head<3>().norm();
  in.L = in.light.template cast<Wide>();
  in.PL = in.P.dot(in.L);
  in.sigma = in.P.cwiseAbs().dot(in.L.cwiseAbs());
  return in;
}

// A refusal (nullopt) is only allowed where the light lies on the plane up to rounding.
template <class T>
void assert_refusal_is_justified(const ShadowInputs<T>& in) {
  RC_LOG() << "the adapter refused the input; P·L = " << static_cast<double>(in.PL) << "\n";
  RC_ASSERT(std::abs(in.PL) <= rounding<T>(kShadowMatrixOps, in.sigma));
}

template <class T>
W4 homogeneous(const Vec3<double>& p) {
  const Vec3<T> q = p.cast<T>();
  return W4(q.x(), q.y(), q.z(), 1);
}

// Per-component bound of |ΔS · v| for the matrix's rounding ΔS: cε (A |v|).
template <class T>
W4 product_bound(const ShadowInputs<T>& in, const W4& v) {
  return W4(in.A() * v.cwiseAbs()) * rounding<T>(kShadowMatrixOps, 1);
}

// ---- the shadow matrix ---------------------------------------------------------------------------

// S v lies on the plane (after the divide) for every point v.
template <class T>
void projected_point_lies_on_plane(const MathFunctions<T>& f) {
  const auto plane = *gen::plane();
  const auto light = *gen::light(plane);
  const auto p = *gen::point();
  const auto in = shadow_inputs<T>(plane.abcd(), light.L);
  const auto s = f.shadow_matrix(in.plane, in.light);
  if (!s) return assert_refusal_is_justified(in);
  const W4 v = homogeneous<T>(p);
  const W4 h = s->template cast<Wide>() * v;
  RC_PRE(h.w() != 0);  // v at the light's height: projected to infinity, no point to check
  const Wide dist = in.P.dot(h) / h.w();  // signed distance of the projected point to the plane
  const Wide tol = in.P.cwiseAbs().dot(product_bound(in, v)) / std::abs(h.w());
  RC_LOG() << "S = " << str(*s) << "\nprojected " << str(h) << " distance " << static_cast<double>(dist)
           << " tolerance " << static_cast<double>(tol) << "\n";
  RC_ASSERT(std::abs(dist) <= tol);
}

// For v on the plane, S v = (P·L) v: the point stays where it is (and S is not scaled).
template <class T>
void points_on_plane_stay(const MathFunctions<T>& f) {
  const auto plane = *gen::plane();
  const auto light = *gen::light(plane);
  const auto p = *gen::point_on(plane);
  const auto in = shadow_inputs<T>(plane.abcd(), light.L);
  const auto s = f.shadow_matrix(in.plane, in.light);
  if (!s) return assert_refusal_is_justified(in);
  const W4 v = homogeneous<T>(p);
  const W4 h = s->template cast<Wide>() * v;
  // v rounded to T lies off the plane by P·v; the exact S moves it by −L (P·v): part of the bound.
  const W4 tol = product_bound(in, v) + in.L.cwiseAbs() * std::abs(in.P.dot(v));
  const W4 diff = h - in.PL * v;
  RC_LOG() << "S = " << str(*s) << "\nS v = " << str(h) << " (P.L) v = " << str(W4(in.PL * v)) << " tolerance "
           << str(tol) << "\n";
  RC_ASSERT((diff.cwiseAbs().array() <= tol.array()).all());
}

// The permanent of the 3 × 3 matrix of absolute values: a bound of a determinant's change.
inline Wide permanent3(const Vec3<Wide>& a, const Vec3<Wide>& b, const Vec3<Wide>& c) {
  return a[0] * (b[1] * c[2] + b[2] * c[1]) + a[1] * (b[0] * c[2] + b[2] * c[0]) + a[2] * (b[0] * c[1] + b[1] * c[0]);
}

// v, L and S v are collinear as homogeneous points: every 3 × 3 minor of [v L Sv] vanishes.
template <class T>
void assert_collinear(const ShadowInputs<T>& in, const Mat4<T>& s, const W4& v) {
  const W4 h = s.template cast<Wide>() * v;
  const W4 dh = product_bound(in, v);
  for (int skip = 0; skip < 4; ++skip) {
    Vec3<Wide> a, b, c, da;
    for (int r = 0, k = 0; r < 4; ++r)
      if (r != skip) a[k] = v[r], b[k] = in.L[r], c[k] = h[r], da[k] = dh[r], ++k;
    Mat3<Wide> m;
    m << a, b, c;
    const Wide minor = m.determinant();
    // |det(a, b, c + Δ) − det(a, b, c)| ≤ perm(|a|, |b|, |Δ|); plus the determinant's own rounding.
    const Wide tol = permanent3(a.cwiseAbs(), b.cwiseAbs(), da) +
                     rounding<Wide>(16, permanent3(a.cwiseAbs(), b.cwiseAbs(), c.cwiseAbs()));
    RC_LOG() << "minor without row " << skip << ": " << static_cast<double>(minor) << " tolerance "
             << static_cast<double>(tol) << "\n";
    RC_ASSERT(std::abs(minor) <= tol);
  }
}

// The point, the (point) light and the projected point are collinear.
template <class T>
void point_light_and_projection_are_collinear(const MathFunctions<T>& f) {
  const auto plane = *gen::plane();
  const auto light = *gen::point_light(plane);
  const auto p = *gen::point();
  const auto in = shadow_inputs<T>(plane.abcd(), light.L);
  const auto s = f.shadow_matrix(in.plane, in.light);
  if (!s) return assert_refusal_is_justified(in);
  assert_collinear(in, *s, homogeneous<T>(p));
}

// A directional light projects along its direction: p' − p is parallel to L.xyz (the same minors,
// L being the point at infinity of that direction).
template <class T>
void directional_light_projects_along_its_direction(const MathFunctions<T>& f) {
  const auto plane = *gen::plane();
  const auto light = *gen::directional_light(plane);
  const auto p = *gen::point();
  const auto in = shadow_inputs<T>(plane.abcd(), light.L);
  const auto s = f.shadow_matrix(in.plane, in.light);
  if (!s) return assert_refusal_is_justified(in);
  assert_collinear(in, *s, homogeneous<T>(p));
}

// S L = 0: the light itself has no shadow.
template <class T>
void light_is_in_the_kernel(const MathFunctions<T>& f) {
  const auto plane = *gen::plane();
  const auto light = *gen::light(plane);
  const auto in = shadow_inputs<T>(plane.abcd(), light.L);
  const auto s = f.shadow_matrix(in.plane, in.light);
  if (!s) return assert_refusal_is_justified(in);
  const W4 h = s->template cast<Wide>() * in.L;
  const W4 tol = product_bound(in, in.L);
  RC_LOG() << "S L = " << str(h) << " tolerance " << str(tol) << "\n";
  RC_ASSERT((h.cwiseAbs().array() <= tol.array()).all());
}

// S² = (P·L) S with P normalised: projecting twice is projecting once (and S is not scaled).
template <class T>
void projecting_twice_is_projecting_once(const MathFunctions<T>& f) {
  const auto plane = *gen::plane();
  const auto light = *gen::light(plane);
  const auto in = shadow_inputs<T>(plane.abcd(), light.L);
  const auto s = f.shadow_matrix(in.plane, in.light);
  if (!s) return assert_refusal_is_justified(in);
  const WM sw = s->template cast<Wide>();
  const WM diff = sw * sw - in.PL * sw;
  // (S + Δ)² − (P·L)(S + Δ) − 0 ≈ SΔ + ΔS − (P·L)Δ with |Δ| ≤ cε A and |S| ≤ A.
  const WM a = in.A();
  const WM tol = (WM(2 * a * a) + in.sigma * a) * rounding<T>(kShadowMatrixOps, 1);
  RC_LOG() << "S = " << str(*s) << "\nS^2 - (P.L) S = " << str(diff) << "\n";
  RC_ASSERT((diff.cwiseAbs().array() <= tol.array()).all());
}

// Scaling the plane by k > 0 changes nothing after the divide.
template <class T>
void scaling_the_plane_changes_nothing(const MathFunctions<T>& f) {
  const auto plane = *gen::plane();
  const auto light = *gen::light(plane);
  const auto p = *gen::point();
  const double k = *gen::power_of_ten(-3, 3);
  const auto in = shadow_inputs<T>(plane.abcd(), light.L);
  const auto s1 = f.shadow_matrix(in.plane, in.light);
  const auto s2 = f.shadow_matrix(Vec4<T>(in.plane * static_cast<T>(k)), in.light);
  if (!s1 || !s2) return assert_refusal_is_justified(in);
  const W4 v = homogeneous<T>(p);
  const W4 h1 = s1->template cast<Wide>() * v, h2 = s2->template cast<Wide>() * v;
  RC_PRE(h1.w() != 0 && h2.w() != 0);
  const Vec3<Wide> q1 = h1.template head<3>() / h1.w(), q2 = h2.template head<3>() / h2.w();
  // Each projected point is off by (|Δh.xyz| + |q| |Δh.w|) / |w|; the scaled plane's rounding to T
  // perturbs P by another few ε, covered by the count of operations.
  const W4 dh = 2 * product_bound(in, v);
  const Vec3<Wide> tol = (dh.template head<3>() + q1.cwiseAbs() * dh.w()) / std::abs(h1.w()) +
                         (dh.template head<3>() + q2.cwiseAbs() * dh.w()) / std::abs(h2.w());
  RC_LOG() << "k = " << k << " projected " << str(q1) << " vs " << str(q2) << "\n";
  RC_ASSERT(((q1 - q2).cwiseAbs().array() <= tol.array()).all());
}

// The D3DX layout is the transpose: used with ROW vectors (v' = v D) it projects onto the plane,
// and it equals Sᵀ entry by entry up to rounding.
template <class T>
void d3dx_layout_is_the_transpose(const MathFunctions<T>& f) {
  const auto plane = *gen::plane();
  const auto light = *gen::light(plane);
  const auto p = *gen::point();
  const auto in = shadow_inputs<T>(plane.abcd(), light.L);
  const auto d = f.shadow_matrix_d3dx(in.plane, in.light);
  const auto s = f.shadow_matrix(in.plane, in.light);
  if (!d || !s) return assert_refusal_is_justified(in);
  const W4 v = homogeneous<T>(p);
  const W4 h = (v.transpose() * d->template cast<Wide>()).transpose();  // row vector times D
  RC_PRE(h.w() != 0);
  const Wide dist = in.P.dot(h) / h.w();
  const Wide tol = in.P.cwiseAbs().dot(product_bound(in, v)) / std::abs(h.w());
  RC_LOG() << "D = " << str(*d) << "\nv D = " << str(h) << " distance " << static_cast<double>(dist) << " tolerance "
           << static_cast<double>(tol) << "\n";
  RC_ASSERT(std::abs(dist) <= tol);
  const WM diff = d->template cast<Wide>() - s->transpose().template cast<Wide>();
  const WM etol = WM(in.A().transpose()) * rounding<T>(2 * kShadowMatrixOps, 1);
  RC_ASSERT((diff.cwiseAbs().array() <= etol.array()).all());
}

// ---- projections -----------------------------------------------------------------------------------

template <class T>
struct ProjectionCase {
  T fovy, aspect, near, far;
  ClipConvention conv;
};

template <class T>
ProjectionCase<T> projection_case(const gen::CameraCase& c, const std::vector<ClipConvention>& convs) {
  return {static_cast<T>(c.fovy()), static_cast<T>(c.aspect), static_cast<T>(c.near), static_cast<T>(c.far()),
          convs[static_cast<std::size_t>(c.convention)]};
}

template <class T>
std::pair<Wide, Wide> near_far_depth(const ClipConvention& c) {
  if (c.order == DepthOrder::Reversed) return {1, 0};
  return {c.depth == DepthRange::NegOneToOne ? -1 : 0, 1};
}

// A view-space point at distance t along the view axis, at NDC-ish position (x, y) ∈ [−1, 1]².
template <class T>
Vec4<T> view_point(const ProjectionCase<T>& pc, Wide x, Wide y, Wide t) {
  const Wide th = std::tan(static_cast<Wide>(pc.fovy) / 2);
  const Wide s = pc.conv.hand == Handedness::Right ? -1 : 1;
  return Vec4<T>(static_cast<T>(x * th * pc.aspect * t), static_cast<T>(y * th * t), static_cast<T>(s * t), T(1));
}

// NDC depth of a view-space point computed in T (as a GPU would), and its rounding bound: the
// third row's 4-term sum (4 + 1 for the divide), relative to the terms' magnitude over |w|.
template <class T>
std::pair<Wide, Wide> ndc_depth(const Mat4<T>& m, const Vec4<T>& v) {
  const Vec4<T> c = m * v;
  const Wide mag = (m.row(2).cwiseAbs() * v.cwiseAbs()).value();
  return {static_cast<Wide>(c.z()) / static_cast<Wide>(c.w()),
          rounding<T>(8, mag / std::abs(static_cast<Wide>(c.w()))) + rounding<T>(2, 1)};
}

// The finite projection tends to the infinite one: |P(far) − P(∞)| ≤ 2 n max(1, n) / (far − n)
// entry by entry (the exact difference of the depth rows), plus rounding.
template <class T>
void finite_projection_tends_to_infinite(const MathFunctions<T>& f) {
  const auto cam = *gen::camera(static_cast<int>(f.finite_conventions.size()));
  const auto pc = projection_case<T>(cam, f.finite_conventions);
  const bool infinite_supported = std::any_of(f.infinite_conventions.begin(), f.infinite_conventions.end(), [&](auto c) {
    return c.hand == pc.conv.hand && c.depth == pc.conv.depth && c.order == pc.conv.order;
  });
  RC_PRE(infinite_supported);
  const auto pf = f.perspective(pc.fovy, pc.aspect, pc.near, pc.far, pc.conv);
  const auto pi = f.perspective_infinite(pc.fovy, pc.aspect, pc.near, T(0), pc.conv);
  RC_ASSERT(pf.has_value());
  RC_ASSERT(pi.has_value());
  const Wide n = pc.near, far = pc.far;
  const Wide limit = 2 * n * std::max<Wide>(1, n) / (far - n);
  const WM diff = (pf->template cast<Wide>() - pi->template cast<Wide>()).cwiseAbs();
  const WM tol = WM::Constant(limit) + (pf->cwiseAbs() + pi->cwiseAbs()).template cast<Wide>() * rounding<T>(8, 1);
  RC_LOG() << "P(far) = " << str(*pf) << "\nP(inf) = " << str(*pi) << "\nbound " << static_cast<double>(limit) << "\n";
  RC_ASSERT((diff.array() <= tol.array()).all());
}

// With the safe epsilon, a direction (w = 0) inside the view frustum is never clipped by the far
// plane: its clip z stays strictly inside (z < w; reversed-Z: z > 0), with P · V multiplied in T.
template <class T>
void directions_survive_the_infinite_far_plane(const MathFunctions<T>& f) {
  const auto cam = *gen::camera(static_cast<int>(f.infinite_conventions.size()));
  RC_PRE(gen::well_posed(cam));
  const auto pc = projection_case<T>(cam, f.infinite_conventions);
  const auto p = f.perspective_infinite(pc.fovy, pc.aspect, pc.near, static_cast<T>(kSafeInfiniteEpsilonFloat), pc.conv);
  RC_ASSERT(p.has_value());
  const auto view = look_at<T>(cam.eye.cast<T>(), cam.target().cast<T>(), cam.up.cast<T>(), pc.conv.hand);
  RC_PRE(view.ok());
  const Mat4<T> pv = *p * *view;
  const Mat3<Wide> to_world = view->template topLeftCorner<3, 3>().template cast<Wide>().transpose();
  // 64 directions per camera on an 8 × 8 grid of the screen with a random offset: many sums, some
  // with cancellation, which is where rounding pushes a direction past the far plane.
  const Wide ox = *gen::uniform(0, 1), oy = *gen::uniform(0, 1);
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j) {
      const Wide x = (2 * (i + ox) / 8 - 1) * Wide(0.999), y = (2 * (j + oy) / 8 - 1) * Wide(0.999);
      const Vec4<T> vp = view_point(pc, x, y, 1);
      const Vec3<Wide> dw = to_world * vp.template head<3>().template cast<Wide>();
      const Vec4<T> d(static_cast<T>(dw.x()), static_cast<T>(dw.y()), static_cast<T>(dw.z()), T(0));
      const Vec4<T> c = pv * d;
      RC_LOG() << "direction " << str(d) << " clip " << str(c) << "\n";
      RC_ASSERT(c.w() > T(0));
      if (pc.conv.order == DepthOrder::Reversed) RC_ASSERT(c.z() > T(0));
      else RC_ASSERT(c.z() < c.w());
    }
}

// Depth is monotonic along a view ray: farther points get larger depth (smaller with reversed-Z),
// in exact arithmetic on the matrix as returned and up to rounding when computed in T.
template <class T>
void depth_is_monotonic_along_a_view_ray(const MathFunctions<T>& f) {
  const auto cam = *gen::camera(static_cast<int>(f.finite_conventions.size()));
  const bool infinite = *rc::gen::arbitrary<bool>();
  const auto& convs = infinite ? f.infinite_conventions : f.finite_conventions;
  RC_PRE(static_cast<std::size_t>(cam.convention) < convs.size());
  const auto pc = projection_case<T>(cam, convs);
  const auto m = infinite ? f.perspective_infinite(pc.fovy, pc.aspect, pc.near, T(0), pc.conv)
                          : f.perspective(pc.fovy, pc.aspect, pc.near, pc.far, pc.conv);
  RC_ASSERT(m.has_value());
  const Wide x = *gen::centered(1), y = *gen::centered(1);
  const Wide reach = infinite ? Wide(pc.near) * Wide(1e6) : Wide(pc.far);
  const Wide u1 = *gen::uniform(0, 1), u2 = *gen::uniform(0, 1);
  RC_PRE(u1 != u2);
  const Wide t1 = pc.near + (reach - pc.near) * std::min(u1, u2), t2 = pc.near + (reach - pc.near) * std::max(u1, u2);
  const Vec4<T> v1 = view_point(pc, x, y, t1), v2 = view_point(pc, x, y, t2);
  RC_PRE(v1 != v2);
  const Wide sign = pc.conv.order == DepthOrder::Reversed ? -1 : 1;
  // Exact arithmetic on the returned matrix: strictly monotonic.
  const WM mw = m->template cast<Wide>();
  const W4 c1 = mw * v1.template cast<Wide>(), c2 = mw * v2.template cast<Wide>();
  RC_LOG() << "M = " << str(*m) << "\nt1 = " << static_cast<double>(t1) << " t2 = " << static_cast<double>(t2) << "\n";
  RC_ASSERT(sign * (c2.z() / c2.w() - c1.z() / c1.w()) > 0);
  // In T: monotonic up to the rounding of each depth.
  const auto [d1, tol1] = ndc_depth(*m, v1);
  const auto [d2, tol2] = ndc_depth(*m, v2);
  RC_ASSERT(sign * (d2 - d1) >= -(tol1 + tol2));
}

// The near plane maps to −1 (OpenGL) or 0 (Direct3D), 1 with reversed-Z, anywhere in the frustum.
template <class T>
void near_maps_to_the_conventions_depth(const MathFunctions<T>& f) {
  const auto cam = *gen::camera(static_cast<int>(f.finite_conventions.size()));
  const bool infinite = *rc::gen::arbitrary<bool>();
  const auto& convs = infinite ? f.infinite_conventions : f.finite_conventions;
  RC_PRE(static_cast<std::size_t>(cam.convention) < convs.size());
  const auto pc = projection_case<T>(cam, convs);
  const T eps = infinite ? static_cast<T>(kSafeInfiniteEpsilonFloat) : T(0);
  const auto m = infinite ? f.perspective_infinite(pc.fovy, pc.aspect, pc.near, eps, pc.conv)
                          : f.perspective(pc.fovy, pc.aspect, pc.near, pc.far, pc.conv);
  RC_ASSERT(m.has_value());
  const Wide x = *gen::centered(1), y = *gen::centered(1);
  const Vec4<T> v = view_point(pc, x, y, pc.near);
  const auto [depth, tol] = ndc_depth(*m, v);
  const Wide want = near_far_depth<T>(pc.conv).first;
  RC_LOG() << "M = " << str(*m) << "\nnear depth " << static_cast<double>(depth) << " want " << static_cast<double>(want)
           << " tolerance " << static_cast<double>(tol) << "\n";
  RC_ASSERT(std::abs(depth - want) <= tol);
}

// ---- clip-space x and y -------------------------------------------------------------------------------

// Rounding steps behind an NDC x or y: an x/y entry of a projection takes at most four (a tangent, a
// product, a sum or difference, a division: 1 / (aspect tan(fovy/2)), (r + l) / (r − l)), and the
// view-space point one more (the property builds it in Wide and rounds it to T). 8 leaves room for
// libm's tangent (up to 1 ulp, two rounding steps) and other expression orders (GLM's infinite
// form builds 2n / (right − left) through range = tan(fovy/2) n: five steps). Measured over
// 3 × 10^4 cases per property on shadowref and on GLM: the largest error needed between 1 and 2
// (GLM's infinite form in float), so 8 keeps a factor of 4.
inline constexpr Wide kClipOps = 8;

// The NDC of the view-space point v under m, evaluated in Wide from the T values (so only the
// matrix's and the point's rounding are judged), with a bound of that rounding per coordinate:
// entries and coordinates each off by kClipOps ε (relative) move clip row i by kClipOps ε times the
// magnitude of its terms, |m_i|·|v|, and ndc_i = c_i / w by (that + |ndc_i| times w's) / |w|.
// A reversed depth row is row 3 minus row 2, so its terms include w's.
struct Ndc {
  Vec3<Wide> at, tol;
  Wide w = 0;
};

template <class T>
Ndc ndc_of(const Mat4<T>& m, const Vec4<T>& v) {
  const WM mw = m.template cast<Wide>();
  const W4 vw = v.template cast<Wide>();
  const W4 c = mw * vw;
  const W4 mag = mw.cwiseAbs() * vw.cwiseAbs();
  Ndc n;
  n.w = c.w();
  n.at = c.template head<3>() / c.w();
  for (int i = 0; i < 3; ++i)
    n.tol[i] = rounding<T>(kClipOps, (mag[i] + std::abs(n.at[i]) * mag[3] + (i == 2 ? mag[3] : 0)) / std::abs(c.w()));
  return n;
}

// The projections a view-volume property can ask an adapter for.
enum class Projection { Perspective, PerspectiveInfinite, Frustum, Ortho };

inline std::ostream& operator<<(std::ostream& os, Projection p) {
  const char* names[] = {"perspective", "perspective_infinite", "frustum", "ortho"};
  return os << names[static_cast<int>(p)];
}

template <class T>
const std::vector<ClipConvention>& conventions_of(const MathFunctions<T>& f, Projection p) {
  switch (p) {
    case Projection::Perspective: return f.finite_conventions;
    case Projection::PerspectiveInfinite: return f.infinite_conventions;
    case Projection::Frustum: return f.frustum_conventions;
    case Projection::Ortho: break;
  }
  return f.ortho_conventions;
}

// The projections the adapter has (in at least one convention).
template <class T>
std::vector<Projection> projections_of(const MathFunctions<T>& f) {
  std::vector<Projection> out;
  for (Projection p : {Projection::Perspective, Projection::PerspectiveInfinite, Projection::Frustum, Projection::Ortho})
    if (!conventions_of(f, p).empty()) out.push_back(p);
  return out;
}

// One view volume as the scalar T sees it: the projection, its parameters, its convention.
template <class T>
struct ViewVolume {
  Projection kind = Projection::Perspective;
  T fovy = 0, aspect = 0;         // perspective (finite and infinite)
  T l = 0, r = 0, b = 0, t = 0;   // frustum: the near rectangle; ortho: the box's sides
  T near = 0, far = 0;            // (the infinite perspective ignores far)
  T epsilon = 0;                  // the infinite perspective's
  ClipConvention conv;
};

template <class T>
std::ostream& operator<<(std::ostream& os, const ViewVolume<T>& v) {
  os << std::setprecision(std::numeric_limits<T>::max_digits10) << v.kind << " " << str(v.conv);
  if (v.kind == Projection::Perspective || v.kind == Projection::PerspectiveInfinite)
    os << " fovy=" << v.fovy << " aspect=" << v.aspect;
  else
    os << " l=" << v.l << " r=" << v.r << " b=" << v.b << " t=" << v.t;
  os << " near=" << v.near;
  if (v.kind == Projection::PerspectiveInfinite) return os << " epsilon=" << v.epsilon;
  return os << " far=" << v.far;
}

// A convention of the adapter's list for `kind`, drawn by the property.
template <class T>
ClipConvention draw_convention(const MathFunctions<T>& f, Projection kind) {
  const auto& convs = conventions_of(f, kind);
  RC_PRE(!convs.empty());
  return convs[*rc::gen::inRange<std::size_t>(0, convs.size())];
}

// A generated view volume of the given kind, in a convention the adapter lists for it.
template <class T>
ViewVolume<T> draw_volume(const MathFunctions<T>& f, Projection kind) {
  ViewVolume<T> v;
  v.kind = kind;
  v.conv = draw_convention(f, kind);
  if (kind == Projection::Perspective || kind == Projection::PerspectiveInfinite) {
    const auto c = *gen::lens();
    v.fovy = static_cast<T>(c.fovy()), v.aspect = static_cast<T>(c.aspect);
    v.near = static_cast<T>(c.near), v.far = static_cast<T>(c.far());
    if (kind == Projection::PerspectiveInfinite)
      v.epsilon = static_cast<T>(*rc::gen::element(0.0, kSafeInfiniteEpsilonFloat, 1.0 / 64));
  } else if (kind == Projection::Frustum) {
    const auto c = *gen::off_centre_frustum();
    v.l = static_cast<T>(c.l()), v.r = static_cast<T>(c.r()), v.b = static_cast<T>(c.b()), v.t = static_cast<T>(c.t());
    v.near = static_cast<T>(c.near), v.far = static_cast<T>(c.far());
  } else {
    const auto c = *gen::ortho_box();
    v.l = static_cast<T>(c.l()), v.r = static_cast<T>(c.r()), v.b = static_cast<T>(c.b()), v.t = static_cast<T>(c.t());
    v.near = static_cast<T>(c.n()), v.far = static_cast<T>(c.f());
  }
  return v;
}

// The adapter's matrix for the volume; a refusal fails the property (every generated volume is
// well posed in float and double).
template <class T>
Mat4<T> projection_of(const MathFunctions<T>& f, const ViewVolume<T>& v) {
  std::optional<Mat4<T>> m;
  switch (v.kind) {
    case Projection::Perspective: m = f.perspective(v.fovy, v.aspect, v.near, v.far, v.conv); break;
    case Projection::PerspectiveInfinite: m = f.perspective_infinite(v.fovy, v.aspect, v.near, v.epsilon, v.conv); break;
    case Projection::Frustum: m = f.frustum(v.l, v.r, v.b, v.t, v.near, v.far, v.conv); break;
    case Projection::Ortho: m = f.ortho(v.l, v.r, v.b, v.t, v.near, v.far, v.conv); break;
  }
  RC_LOG() << v << "\n";
  RC_ASSERT(m.has_value());
  RC_LOG() << "M = " << str(*m) << "\n";
  return *m;
}

// The view-space point the volume should map to NDC (u, v), at distance d in front of the eye
// (z = −d in RH, +d in LH), computed in Wide and rounded to T:
//   perspective: x = u d tan(fovy/2) aspect, y = v d tan(fovy/2) (the edges of the VERTICAL field);
//   frustum:     (x, y) = d / near times the near-rectangle point ((l+r)/2 + u (r−l)/2, (b+t)/2 + v (t−b)/2);
//   ortho:       (x, y) = that rectangle point itself, whatever d.
template <class T>
Vec4<T> point_at(const ViewVolume<T>& vol, Wide u, Wide v, Wide d) {
  const Wide z = (vol.conv.hand == Handedness::Right ? -1 : 1) * d;
  Wide x, y;
  if (vol.kind == Projection::Perspective || vol.kind == Projection::PerspectiveInfinite) {
    const Wide th = std::tan(static_cast<Wide>(vol.fovy) / 2);
    x = u * d * th * static_cast<Wide>(vol.aspect);
    y = v * d * th;
  } else {
    const Wide l = vol.l, r = vol.r, b = vol.b, t = vol.t;
    x = (l + r) / 2 + u * (r - l) / 2;
    y = (b + t) / 2 + v * (t - b) / 2;
    if (vol.kind == Projection::Frustum) {
      x *= d / static_cast<Wide>(vol.near);
      y *= d / static_cast<Wide>(vol.near);
    }
  }
  return Vec4<T>(static_cast<T>(x), static_cast<T>(y), static_cast<T>(z), T(1));
}

// A distance in front of the eye inside the volume's depth extent: log-uniform from near to far
// for perspectives (to near · 10^6 for the infinite one), uniform from near to far for ortho.
template <class T>
Wide draw_distance(const ViewVolume<T>& v) {
  const Wide n = v.near, u = *gen::uniform(0, 1);
  if (v.kind == Projection::Ortho) return n + (static_cast<Wide>(v.far) - n) * u;
  const Wide reach = v.kind == Projection::PerspectiveInfinite ? n * Wide(1e6) : static_cast<Wide>(v.far);
  return n * std::pow(reach / n, u);
}

// The point for NDC (u, v) at distance d lands in front of the eye (w > 0), at (u, v).
template <class T>
void assert_lands_at(const Mat4<T>& m, const ViewVolume<T>& vol, Wide u, Wide v, Wide d) {
  const Vec4<T> p = point_at(vol, u, v, d);
  const Ndc n = ndc_of(m, p);
  RC_LOG() << "view " << str(p) << " should land at (" << static_cast<double>(u) << ", " << static_cast<double>(v)
           << "): ndc (" << static_cast<double>(n.at.x()) << ", " << static_cast<double>(n.at.y()) << ") w "
           << static_cast<double>(n.w) << " tolerance (" << static_cast<double>(n.tol.x()) << ", "
           << static_cast<double>(n.tol.y()) << ")\n";
  RC_ASSERT(n.w > 0);
  RC_ASSERT(std::abs(n.at.x() - u) <= n.tol.x());
  RC_ASSERT(std::abs(n.at.y() - v) <= n.tol.y());
}

// The volume's edges land on the NDC square's edges at one distance: the top edge (anywhere along
// it) on ndc.y = +1, the bottom on −1, the right on ndc.x = +1, the left on −1, the four corners
// on (±1, ±1), the centre on (0, 0), and a point at fractions (u, v) of the half-extents on (u, v).
template <class T>
void assert_maps_onto_the_ndc_square(const Mat4<T>& m, const ViewVolume<T>& vol) {
  const Wide d = draw_distance(vol);
  const Wide u = *gen::centered(1), v = *gen::centered(1);
  assert_lands_at(m, vol, u, 1, d);
  assert_lands_at(m, vol, u, -1, d);
  assert_lands_at(m, vol, 1, v, d);
  assert_lands_at(m, vol, -1, v, d);
  for (Wide cx : {-1, 1})
    for (Wide cy : {-1, 1}) assert_lands_at(m, vol, cx, cy, d);
  assert_lands_at(m, vol, 0, 0, d);
  assert_lands_at(m, vol, u, v, d);
}

// Perspective, finite and infinite, in every listed convention: a view-space point on the top edge
// of the VERTICAL field of view (y = |z| tan(fovy/2)) lands on ndc.y = +1, on the right edge
// (x = |z| tan(fovy/2) aspect) on ndc.x = +1, and so on (assert_maps_onto_the_ndc_square), at
// any distance. A projection built from the horizontal field of view, or with the aspect
// inverted, passes every other property here and fails this one.
template <class T>
void perspective_maps_the_field_of_view_onto_the_ndc_square(const MathFunctions<T>& f) {
  const bool infinite = *rc::gen::arbitrary<bool>();
  const auto vol = draw_volume(f, infinite ? Projection::PerspectiveInfinite : Projection::Perspective);
  assert_maps_onto_the_ndc_square(projection_of(f, vol), vol);
}

// The off-centre frustum maps its near rectangle [l, r] × [b, t] onto the NDC square at every
// depth: the rays through its corners land on (±1, ±1), through its centre on (0, 0), through its
// edges on the square's edges — rectangles that do not contain the view axis included.
template <class T>
void frustum_maps_its_near_rectangle_onto_the_ndc_square(const MathFunctions<T>& f) {
  const auto vol = draw_volume(f, Projection::Frustum);
  assert_maps_onto_the_ndc_square(projection_of(f, vol), vol);
}

// The orthographic projection maps its box's sides onto the NDC square's at every depth: x = l on
// −1, x = r on +1, y = b on −1, y = t on +1, the centre on (0, 0).
template <class T>
void ortho_maps_its_box_onto_the_ndc_square(const MathFunctions<T>& f) {
  const auto vol = draw_volume(f, Projection::Ortho);
  assert_maps_onto_the_ndc_square(projection_of(f, vol), vol);
}

// Handedness: a point in front of the eye (z < 0 in RH, z > 0 in LH) is in front after the
// projection, w > 0, and the same point mirrored behind the eye has w < 0 (perspectives and
// frustum; the sign is exact: w = ±z). An orthographic projection has w = 1 everywhere, so there
// the view direction shows in depth: the box's near face (z = −near in RH, +near in LH) gets the
// convention's near depth and its far face the far depth.
template <class T>
void points_in_front_of_the_eye_are_in_front(const MathFunctions<T>& f) {
  const auto vol = draw_volume(f, *rc::gen::elementOf(projections_of(f)));
  const Mat4<T> m = projection_of(f, vol);
  const Wide u = *gen::centered(2), v = *gen::centered(2);
  if (vol.kind == Projection::Ortho) {
    const auto [near_depth, far_depth] = near_far_depth<T>(vol.conv);
    for (const auto& [d, want] : {std::pair<Wide, Wide>(vol.near, near_depth), std::pair<Wide, Wide>(vol.far, far_depth)}) {
      const Vec4<T> p = point_at(vol, u, v, d);
      const Ndc n = ndc_of(m, p);
      RC_LOG() << "view " << str(p) << " depth " << static_cast<double>(n.at.z()) << " want " << static_cast<double>(want)
               << " tolerance " << static_cast<double>(n.tol.z()) << "\n";
      RC_ASSERT(n.w > 0);
      RC_ASSERT(std::abs(n.at.z() - want) <= n.tol.z());
    }
    return;
  }
  const Wide d = static_cast<Wide>(vol.near) * *gen::power_of_ten(-3, 6);
  const Vec4<T> front = point_at(vol, u, v, d);
  const Vec4<T> behind(front.x(), front.y(), -front.z(), T(1));
  const W4 cf = m.template cast<Wide>() * front.template cast<Wide>();
  const W4 cb = m.template cast<Wide>() * behind.template cast<Wide>();
  RC_LOG() << "in front " << str(front) << " clip " << str(cf) << "; behind " << str(behind) << " clip " << str(cb) << "\n";
  RC_ASSERT(cf.w() > 0);
  RC_ASSERT(cb.w() < 0);
}

// NDC x and y do not depend on the depth parameters: two volumes that differ only in near, far,
// epsilon, finite or infinite, depth range, depth order and handedness (the point mirrored in z
// between RH and LH) put the same point at the same ndc.xy, anywhere in view (also beyond the
// volume's sides). Perspectives share fovy and aspect; frusta their near rectangle (and so their
// near); ortho boxes their sides.
template <class T>
void ndc_xy_do_not_depend_on_the_depth_parameters(const MathFunctions<T>& f) {
  const auto a = draw_volume(f, *rc::gen::elementOf(projections_of(f)));
  const bool perspective = a.kind == Projection::Perspective || a.kind == Projection::PerspectiveInfinite;
  ViewVolume<T> b = a;
  if (perspective) {
    std::vector<Projection> kinds;
    for (Projection p : {Projection::Perspective, Projection::PerspectiveInfinite})
      if (!conventions_of(f, p).empty()) kinds.push_back(p);
    const auto other = draw_volume(f, *rc::gen::elementOf(kinds));
    b.kind = other.kind, b.near = other.near, b.far = other.far, b.epsilon = other.epsilon, b.conv = other.conv;
  } else if (a.kind == Projection::Frustum) {
    b.far = static_cast<T>(static_cast<Wide>(a.near) * *gen::power_of_ten(1, 6));
    b.conv = draw_convention(f, a.kind);
  } else {
    // Another near and far at this box's scale (as the generator draws them: near within the
    // scale of the origin, depth 1e-2..1e2 of it), and another convention.
    const Wide scale = std::max({std::abs(static_cast<Wide>(a.l)), std::abs(static_cast<Wide>(a.r)),
                                 std::abs(static_cast<Wide>(a.b)), std::abs(static_cast<Wide>(a.t))});
    const Wide near = scale * *gen::centered(1);
    b.near = static_cast<T>(near);
    b.far = static_cast<T>(near + scale * *gen::power_of_ten(-2, 2));
    b.conv = draw_convention(f, a.kind);
  }
  const Mat4<T> ma = projection_of(f, a), mb = projection_of(f, b);
  const Wide u = *gen::centered(2), v = *gen::centered(2);
  const Wide d = a.kind == Projection::Ortho ? draw_distance(a) : static_cast<Wide>(a.near) * *gen::power_of_ten(-3, 6);
  const Ndc na = ndc_of(ma, point_at(a, u, v, d)), nb = ndc_of(mb, point_at(b, u, v, d));
  RC_LOG() << "ndc.xy (" << static_cast<double>(na.at.x()) << ", " << static_cast<double>(na.at.y()) << ") vs ("
           << static_cast<double>(nb.at.x()) << ", " << static_cast<double>(nb.at.y()) << ")\n";
  RC_ASSERT(std::abs(na.at.x() - nb.at.x()) <= na.tol.x() + nb.tol.x());
  RC_ASSERT(std::abs(na.at.y() - nb.at.y()) <= na.tol.y() + nb.tol.y());
}

}  // namespace shadowref::prop
