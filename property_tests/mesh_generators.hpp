// mesh_generators.hpp — RapidCheck generators of casters: closed meshes (boxes, perturbed spheres
// and tori, convex hulls of random points), open and non-manifold meshes, and lights for them.
//
// Positions are rounded to float even for the double properties, so that the float and double runs
// and Embree (which takes floats) see the very same geometry. Boxes and many lights sit on an
// integer grid on purpose: a light in the plane of a face is the tie that silhouette code must get
// right, and only a grid makes such ties likely.
#pragma once

#include <algorithm>
#include <string>

#include "generators.hpp"
#include "shadowref/adjacency.hpp"
#include "shadowref/primitives.hpp"

namespace shadowref::prop::gen {

struct MeshCase {
  std::string kind;
  TriangleMesh<double> mesh;
  template <class T>
  TriangleMesh<T> as() const {
    TriangleMesh<T> m;
    for (const auto& p : mesh.positions) m.positions.push_back(p.cast<T>());
    m.triangles = mesh.triangles;
    return m;
  }
  friend std::ostream& operator<<(std::ostream& os, const MeshCase& c) {
    os << c.kind << ": " << c.mesh.positions.size() << " vertices, " << c.mesh.triangles.size() << " triangles\n";
    if (c.mesh.triangles.size() <= 24) {
      os << "  positions:";
      for (std::size_t i = 0; i < c.mesh.positions.size(); ++i) os << " " << i << "=" << str(c.mesh.positions[i]);
      os << "\n  triangles:";
      for (const auto& t : c.mesh.triangles) os << " (" << t[0] << " " << t[1] << " " << t[2] << ")";
    }
    return os;
  }
};

inline TriangleMesh<double> rounded_to_float(TriangleMesh<double> m) {
  for (auto& p : m.positions) p = p.cast<float>().cast<double>();
  return m;
}

// An axis-aligned box with integer corners in [−3, 3], sides 1 to 4.
inline rc::Gen<MeshCase> box() {
  return rc::gen::apply(
      [](int x, int y, int z, int sx, int sy, int sz) {
        const Vec3<double> lo(x, y, z);
        return MeshCase{"box", make_box(lo, Vec3<double>(lo + Vec3<double>(sx, sy, sz))).value()};
      },
      rc::gen::inRange(-3, 1), rc::gen::inRange(-3, 1), rc::gen::inRange(-3, 1), rc::gen::inRange(1, 5),
      rc::gen::inRange(1, 5), rc::gen::inRange(1, 5));
}

// Each vertex moved radially by up to ±20 % (keeps a star-shaped surface closed and manifold).
inline TriangleMesh<double> perturbed(TriangleMesh<double> m, const std::vector<int>& bumps, const Vec3<double>& centre,
                                      const Vec3<double>& shift) {
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    const double b = bumps.empty() ? 0 : 0.2 * bumps[i % bumps.size()] / 100.0;
    m.positions[i] = centre + (m.positions[i] - centre) * (1 + b) + shift;
  }
  return rounded_to_float(m);
}

inline rc::Gen<MeshCase> perturbed_sphere() {
  return rc::gen::apply(
      [](double r, int seg, int rings, const std::vector<int>& bumps, const Vec3<double>& shift) {
        return MeshCase{"perturbed sphere",
                        perturbed(make_uv_sphere(r, static_cast<std::uint32_t>(seg), static_cast<std::uint32_t>(rings)).value(),
                                  bumps, Vec3<double>::Zero(), shift)};
      },
      uniform(0.5, 3), rc::gen::inRange(3, 9), rc::gen::inRange(2, 7),
      rc::gen::container<std::vector<int>>(rc::gen::inRange(-100, 101)), vec3(3));
}

inline rc::Gen<MeshCase> perturbed_torus() {
  return rc::gen::apply(
      [](double minor, int maj, int min, const std::vector<int>& bumps, const Vec3<double>& shift) {
        // Radial bumps around each tube centre would need the tube's frame; scaling about the
        // torus centre by ±20 % keeps the torus embedded while the tube is thinner than 0.3 R.
        return MeshCase{"perturbed torus",
                        perturbed(make_torus(2.0, minor, static_cast<std::uint32_t>(maj), static_cast<std::uint32_t>(min)).value(),
                                  bumps, Vec3<double>::Zero(), shift)};
      },
      uniform(0.2, 0.6), rc::gen::inRange(3, 9), rc::gen::inRange(3, 7),
      rc::gen::container<std::vector<int>>(rc::gen::inRange(-100, 101)), vec3(3));
}

// The convex hull of 4 to 10 random points (brute force: every triple with all other points
// strictly on one side is a face, wound so that the others are behind it).
inline TriangleMesh<double> convex_hull(const std::vector<Vec3<double>>& pts) {
  TriangleMesh<double> m;
  m.positions = pts;
  const auto n = static_cast<std::uint32_t>(pts.size());
  for (std::uint32_t i = 0; i < n; ++i)
    for (std::uint32_t j = i + 1; j < n; ++j)
      for (std::uint32_t k = j + 1; k < n; ++k) {
        const Vec3<double> nrm = (pts[j] - pts[i]).cross(pts[k] - pts[i]);
        int pos = 0, neg = 0, zero = 0;
        for (std::uint32_t q = 0; q < n; ++q) {
          if (q == i || q == j || q == k) continue;
          const double s = nrm.dot(pts[q] - pts[i]);
          (s > 0 ? pos : s < 0 ? neg : zero)++;
        }
        if (zero > 0 || (pos > 0 && neg > 0)) continue;
        if (pos > 0) m.triangles.push_back({i, k, j});
        else m.triangles.push_back({i, j, k});
      }
  return m;
}

inline rc::Gen<MeshCase> hull() {
  const auto pts = rc::gen::map(rc::gen::mapcat(rc::gen::inRange<std::size_t>(4, 11),
                                                [](std::size_t n) { return rc::gen::container<std::vector<Vec3<double>>>(n, vec3(3)); }),
                                [](std::vector<Vec3<double>> v) {
                                  for (auto& p : v) p = p.cast<float>().cast<double>();
                                  return v;
                                });
  return rc::gen::map(rc::gen::suchThat(rc::gen::map(pts, convex_hull),
                                        [](const TriangleMesh<double>& m) {
                                          if (m.triangles.size() < 4) return false;
                                          const auto adj = build_adjacency(m);
                                          return adj && adj->report.closed_manifold() && adj->report.degenerate_triangles == 0;
                                        }),
                      [](TriangleMesh<double> m) { return MeshCase{"convex hull", std::move(m)}; });
}

inline rc::Gen<MeshCase> closed_mesh() {
  return rc::gen::oneOf(box(), perturbed_sphere(), perturbed_torus(), hull());
}

// A closed mesh with some of its triangles removed (at least one kept, at least one removed).
inline rc::Gen<MeshCase> open_mesh() {
  return rc::gen::mapcat(closed_mesh(), [](MeshCase c) {
    const auto nt = static_cast<int>(c.mesh.triangles.size());
    return rc::gen::map(rc::gen::container<std::vector<bool>>(static_cast<std::size_t>(nt), rc::gen::arbitrary<bool>()),
                        [c](const std::vector<bool>& keep) {
                          MeshCase o{"open " + c.kind, c.mesh};
                          o.mesh.triangles.clear();
                          for (std::size_t t = 0; t < keep.size(); ++t)
                            if (keep[t] || t == 0) o.mesh.triangles.push_back(c.mesh.triangles[t]);
                          if (o.mesh.triangles.size() == c.mesh.triangles.size()) o.mesh.triangles.pop_back();
                          return o;
                        });
  });
}

// A closed mesh with a fin: one or two triangles on one of its edges (three or four faces there).
inline rc::Gen<MeshCase> non_manifold_mesh() {
  return rc::gen::mapcat(closed_mesh(), [](MeshCase c) {
    return rc::gen::apply(
        [c](int tri, const Vec3<double>& tip, bool two) {
          MeshCase o{"non-manifold " + c.kind, c.mesh};
          const auto& t = c.mesh.triangles[static_cast<std::size_t>(tri) % c.mesh.triangles.size()];
          const auto tip_index = static_cast<std::uint32_t>(o.mesh.positions.size());
          const Vec3<double> mid = (c.mesh.positions[t[0]] + c.mesh.positions[t[1]]) / 2;
          o.mesh.positions.push_back(Vec3<double>(mid + tip).cast<float>().cast<double>());
          o.mesh.triangles.push_back({t[0], t[1], tip_index});
          if (two) o.mesh.triangles.push_back({t[1], t[0], tip_index});  // a two-sided fin
          return o;
        },
        rc::gen::inRange(0, 1 << 20), vec3(3), rc::gen::arbitrary<bool>());
  });
}

inline rc::Gen<MeshCase> any_mesh() {
  return rc::gen::weightedOneOf<MeshCase>({{2, closed_mesh()}, {1, open_mesh()}, {1, non_manifold_mesh()}});
}

// A light for a caster: a point light on the integer grid of [−6, 6]³ (ties with box faces), a
// point light anywhere in [−8, 8]³, an axis-aligned directional light (ties again) or any direction.
inline rc::Gen<LightCase> caster_light() {
  const auto grid = rc::gen::apply(
      [](int x, int y, int z) { return LightCase{Vec4<double>(x, y, z, 1)}; }, rc::gen::inRange(-6, 7),
      rc::gen::inRange(-6, 7), rc::gen::inRange(-6, 7));
  const auto anywhere = rc::gen::map(vec3(8), [](const Vec3<double>& p) {
    const Vec3<float> q = p.cast<float>();
    return LightCase{Vec4<double>(q.x(), q.y(), q.z(), 1)};
  });
  const auto axis = rc::gen::apply(
      [](int a, bool neg) {
        Vec4<double> l = Vec4<double>::Zero();
        l[a] = neg ? -1 : 1;
        return LightCase{l};
      },
      rc::gen::inRange(0, 3), rc::gen::arbitrary<bool>());
  const auto dir = rc::gen::map(direction(), [](const Vec3<double>& d) {
    const Vec3<float> q = d.cast<float>();
    return LightCase{Vec4<double>(q.x(), q.y(), q.z(), 0)};
  });
  return rc::gen::weightedOneOf<LightCase>({{3, grid}, {2, anywhere}, {1, axis}, {1, dir}});
}

}  // namespace shadowref::prop::gen
