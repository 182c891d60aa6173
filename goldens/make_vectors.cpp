// make_vectors.cpp — regenerates goldens/vectors/generated_*.json, the machine-made math test
// vectors engine teams load in their own tests (hand-derived cases live in hand_derived.json and
// are never rewritten).
//
// The expected outputs do NOT come from shadowref's mathlib: shadow matrices come from the classic
// CreateShadowMatrix listing evaluated in long double, finite projections from GLM 0.9.9.8, and
// the infinite / reversed-Z forms (which GLM lacks) from their closed-form rows in long double.
// So the vectors are an independent oracle that vectors_test.cpp holds the library to.
//
//   cmake --build build/release --target make_golden_vectors
//   ./build/release/goldens/make_golden_vectors goldens/vectors
#include <glm/glm.hpp>
#include <glm/ext/matrix_clip_space.hpp>
#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>

namespace {

using nlohmann::ordered_json;
using M4 = std::array<std::array<long double, 4>, 4>;  // m[row][col], canonical

ordered_json rows(const M4& m, bool transpose) {
  ordered_json out = ordered_json::array();
  for (int r = 0; r < 4; ++r) {
    ordered_json row = ordered_json::array();
    for (int c = 0; c < 4; ++c) row.push_back(static_cast<double>(transpose ? m[c][r] : m[r][c]) + 0.0);
    out.push_back(row);
  }
  return out;
}

M4 from_glm(const glm::dmat4& g) {
  M4 m{};
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m[r][c] = g[c][r];
  return m;
}

// The CreateShadowMatrix listing in long double, returned in canonical form (the transpose of
// the listing's _rc fields).
M4 shadow_listing(const std::array<long double, 4>& plane, const std::array<long double, 4>& l) {
  const long double len = std::sqrt(plane[0] * plane[0] + plane[1] * plane[1] + plane[2] * plane[2]);
  const long double a = plane[0] / len, b = plane[1] / len, c = plane[2] / len, d = plane[3] / len;
  const long double dot = a * l[0] + b * l[1] + c * l[2] + d * l[3];
  const long double p[4] = {a, b, c, d};
  M4 canonical{};
  for (int r = 0; r < 4; ++r)      // listing row r: coefficient of input component r
    for (int col = 0; col < 4; ++col)  // listing column: output component
      canonical[col][r] = (r == col ? dot : 0.0L) - l[col] * p[r];
  return canonical;
}

// Closed-form infinite perspective (see projection.hpp's header): s = −1 RH, +1 LH.
M4 infinite_rows(long double fovy, long double aspect, long double n, bool lh, bool zero_to_one, bool reversed,
                 long double eps) {
  const long double s = lh ? 1.0L : -1.0L;
  const long double f = 1.0L / std::tan(fovy / 2.0L);
  M4 m{};
  m[0][0] = f / aspect;
  m[1][1] = f;
  m[3][2] = s;
  m[2][2] = s * (1.0L - eps);
  m[2][3] = zero_to_one ? (eps - 1.0L) * n : (eps - 2.0L) * n;
  if (reversed)
    for (int c = 0; c < 4; ++c) m[2][c] = m[3][c] - m[2][c];
  return m;
}

M4 reverse(M4 m) {
  for (int c = 0; c < 4; ++c) m[2][c] = m[3][c] - m[2][c];
  return m;
}

void write(const std::string& path, const ordered_json& j) {
  std::ofstream out(path);
  out << j.dump(2) << "\n";
  if (!out) {
    std::cerr << "make_golden_vectors: cannot write " << path << "\n";
    std::exit(4);
  }
  std::cout << "wrote " << path << " (" << j.at("cases").size() << " cases)\n";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: make_golden_vectors OUTPUT_DIR   (normally goldens/vectors)\n";
    return 4;
  }
  const std::string dir = argv[1];

  // ---- shadow matrices
  ordered_json shadows{{"description",
                        "Planar shadow matrices S = (P.L) I - L P^T, plane normalised by |(a,b,c)| first. 'canonical': "
                        "column vectors, v' = M v, matrix[i][j] = row i column j. 'd3dx': row vectors, v' = v M, "
                        "matrix[i][j] = field _{i+1}{j+1} (the transpose). Computed by the CreateShadowMatrix listing "
                        "in long double, rounded to double."},
                       {"generator", "goldens/make_vectors.cpp"},
                       {"cases", ordered_json::array()}};
  const std::array<std::array<long double, 4>, 5> planes = {{{0, 1, 0, 0}, {0, 2, 0, -1}, {1, 2, 3, 4},
                                                             {-0.3L, 0.9L, 0.1L, 2.5L}, {0.6L, 0, -0.8L, -3}}};
  const std::array<std::array<long double, 4>, 5> lights = {
      {{2, 6, 1, 1}, {0.5L, 4, -3, 1}, {1, 1, 0.25L, 0}, {-2, 5, 7, 1}, {0.3L, 0.8L, -0.5L, 0}}};
  int k = 0;
  for (const auto& p : planes)
    for (const auto& l : lights) {
      const M4 s = shadow_listing(p, l);
      ordered_json c{{"name", "shadow_" + std::to_string(k++)},
                     {"kind", "shadow"},
                     {"plane", {static_cast<double>(p[0]), static_cast<double>(p[1]), static_cast<double>(p[2]), static_cast<double>(p[3])}},
                     {"light", {static_cast<double>(l[0]), static_cast<double>(l[1]), static_cast<double>(l[2]), static_cast<double>(l[3])}},
                     {"canonical", rows(s, false)},
                     {"d3dx", rows(s, true)}};
      shadows["cases"].push_back(c);
    }
  write(dir + "/generated_shadow_matrices.json", shadows);

  // ---- projections
  ordered_json proj{{"description",
                     "Projections in every convention. hand: rh looks down -z, lh down +z; depth: neg-one-to-one or "
                     "zero-to-one; reversed: near -> 1, far -> 0 (zero-to-one only); far null = infinite with the given "
                     "epsilon (Lengyel). fovy in radians. Finite perspectives and orthos from GLM 0.9.9.8 in double; "
                     "infinite and reversed forms from their closed-form rows in long double."},
                    {"generator", "goldens/make_vectors.cpp"},
                    {"cases", ordered_json::array()}};
  k = 0;
  for (double fovy : {0.5, 1.0471975511965976, 2.0})
    for (double aspect : {1.0, 16.0 / 9.0})
      for (auto [n, f] : {std::pair{0.1, 100.0}, std::pair{1.0, 4.0}})
        for (bool lh : {false, true})
          for (bool zo : {false, true}) {
            M4 m = from_glm(lh ? (zo ? glm::perspectiveLH_ZO(fovy, aspect, n, f) : glm::perspectiveLH_NO(fovy, aspect, n, f))
                               : (zo ? glm::perspectiveRH_ZO(fovy, aspect, n, f) : glm::perspectiveRH_NO(fovy, aspect, n, f)));
            for (bool rev : {false, true}) {
              if (rev && !zo) continue;
              const M4 out = rev ? reverse(m) : m;
              proj["cases"].push_back({{"name", "perspective_" + std::to_string(k++)},
                                       {"kind", "perspective"},
                                       {"fovy", fovy}, {"aspect", aspect}, {"near", n}, {"far", f}, {"epsilon", 0.0},
                                       {"hand", lh ? "lh" : "rh"}, {"depth", zo ? "zero-to-one" : "neg-one-to-one"},
                                       {"reversed", rev}, {"canonical", rows(out, false)}, {"d3dx", rows(out, true)}});
            }
            for (double eps : {0.0, 4.8e-7, 1.0 / 1024.0})
              for (bool rev : {false, true}) {
                if (rev && !zo) continue;
                const M4 inf = infinite_rows(fovy, aspect, n, lh, zo, rev, eps);
                proj["cases"].push_back({{"name", "perspective_" + std::to_string(k++)},
                                         {"kind", "perspective"},
                                         {"fovy", fovy}, {"aspect", aspect}, {"near", n}, {"far", nullptr}, {"epsilon", eps},
                                         {"hand", lh ? "lh" : "rh"}, {"depth", zo ? "zero-to-one" : "neg-one-to-one"},
                                         {"reversed", rev}, {"canonical", rows(inf, false)}, {"d3dx", rows(inf, true)}});
              }
          }
  for (bool lh : {false, true})
    for (bool zo : {false, true}) {
      const double l = -3, r = 5, b = -1, t = 2, n = 0.5, f = 12;
      const M4 m = from_glm(lh ? (zo ? glm::orthoLH_ZO(l, r, b, t, n, f) : glm::orthoLH_NO(l, r, b, t, n, f))
                               : (zo ? glm::orthoRH_ZO(l, r, b, t, n, f) : glm::orthoRH_NO(l, r, b, t, n, f)));
      proj["cases"].push_back({{"name", "ortho_" + std::to_string(k++)},
                               {"kind", "ortho"},
                               {"left", l}, {"right", r}, {"bottom", b}, {"top", t}, {"near", n}, {"far", f},
                               {"hand", lh ? "lh" : "rh"}, {"depth", zo ? "zero-to-one" : "neg-one-to-one"},
                               {"reversed", false}, {"canonical", rows(m, false)}, {"d3dx", rows(m, true)}});
    }
  write(dir + "/generated_projections.json", proj);
  return 0;
}
