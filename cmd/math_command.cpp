// math_command.cpp — `shadowref math`: the matrix calculator (shadow matrices, projections, planes).
//
// Every value comes from mathlib; this file only parses, validates and prints. Output is a table
// for people or, with --json, one JSON object whose "matrix"[i][j] is row i, column j of the chosen
// layout (for D3DX, field _{i+1}{j+1}), with numbers that round-trip to the computed scalar.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "command.hpp"
#include "numbers.hpp"
#include "shadowref/plane.hpp"
#include "shadowref/projection.hpp"
#include "shadowref/shadow_matrix.hpp"

namespace shadowref::cli {
namespace {

using nlohmann::json;

enum class Layout { Canonical, D3dx };
enum class Precision { Float, Double };

const std::map<std::string, Layout> kLayouts{{"canonical", Layout::Canonical}, {"d3dx", Layout::D3dx}};
const std::map<std::string, Precision> kPrecisions{{"float", Precision::Float}, {"double", Precision::Double}};
const std::map<std::string, DepthRange> kDepths{{"neg-one-to-one", DepthRange::NegOneToOne},
                                                 {"zero-to-one", DepthRange::ZeroToOne}};
const std::map<std::string, Handedness> kHands{{"rh", Handedness::Right}, {"lh", Handedness::Left}};

// A JSON number that reads back as exactly `v` in its own precision.
// Every printed value goes through here: -0 prints as 0 (x + 0 turns -0 into +0, nothing else).
template <class T>
json json_number(T v) {
  v = v + T(0);
  if constexpr (std::is_same_v<T, float>) return std::stod(format_number(v));
  else return static_cast<double>(v);
}

template <class T>
std::string text_number(T v) {
  return format_number(v + T(0));
}

template <class T, int N>
json json_vector(const Eigen::Matrix<T, N, 1>& v) {
  json a = json::array();
  for (int i = 0; i < N; ++i) a.push_back(json_number(v[i]));
  return a;
}

template <class T>
json json_matrix(const Mat4<T>& m) {
  json rows = json::array();
  for (int r = 0; r < 4; ++r) {
    json row = json::array();
    for (int c = 0; c < 4; ++c) row.push_back(json_number(m(r, c)));
    rows.push_back(row);
  }
  return rows;
}

template <class T, int N>
std::string text_vector(const Eigen::Matrix<T, N, 1>& v) {
  std::string s = "(";
  for (int i = 0; i < N; ++i) s += (i ? ", " : "") + text_number(v[i]);
  return s + ")";
}

// The matrix as right-aligned columns, one row a line, with the layout's field names for D3DX.
template <class T>
std::string text_matrix(const Mat4<T>& m, Layout layout) {
  std::string cells[4][4];
  std::size_t width = 1;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) {
      cells[r][c] = text_number(m(r, c));
      width = std::max(width, cells[r][c].size());
    }
  std::ostringstream out;
  for (int r = 0; r < 4; ++r) {
    out << (layout == Layout::D3dx ? "  _" + std::to_string(r + 1) + "x  [ " : "  [ ");
    for (int c = 0; c < 4; ++c) out << std::string(width - cells[r][c].size(), ' ') << cells[r][c] << (c < 3 ? "  " : " ]\n");
  }
  return out.str();
}

const char* layout_name(Layout l) { return l == Layout::Canonical ? "canonical" : "d3dx"; }
const char* layout_rule(Layout l) {
  return l == Layout::Canonical ? "column vectors, v' = M * v; matrix[i][j] = row i, column j"
                                : "D3DX row vectors, v' = v * M; matrix[i][j] = field _{i+1}{j+1}";
}
template <class T>
const char* precision_name() {
  return std::is_same_v<T, float> ? "float" : "double";
}

// Throws BadInput with the mathlib reason, prefixed by what was being built.
template <class V>
V require(const Result<V>& r, const std::string& what) {
  if (!r) throw BadInput(what + ": " + r.message());
  return *r;
}

// ---------------------------------------------------------------- shadow-matrix

struct ShadowMatrixArgs {
  std::string plane, light;
  Layout layout = Layout::Canonical;
  Precision precision = Precision::Double;
  bool json = false;
};

template <class T>
void run_shadow_matrix(const ShadowMatrixArgs& a) {
  const std::vector<double> p = parse_numbers("--plane", a.plane, 4);
  const std::vector<double> l = parse_numbers("--light", a.light, 4);
  const Vec4<T> light{T(l[0]), T(l[1]), T(l[2]), T(l[3])};
  const Plane<T> plane = require(plane_from_coefficients(T(p[0]), T(p[1]), T(p[2]), T(p[3])), "--plane");
  const Plane<T> unit = require(normalize(plane), "--plane");
  const Mat4<T> s = require(a.layout == Layout::Canonical ? shadow_matrix(plane, light) : shadow_matrix_d3dx(plane, light),
                             "shadow matrix");
  const T pl = dot(unit, light);
  const char* kind = light[3] == T(0) ? "directional" : "point";
  if (a.json) {
    json j{{"command", "shadow-matrix"},
           {"layout", layout_name(a.layout)},
           {"precision", precision_name<T>()},
           {"plane", json_vector<T, 4>(plane.abcd)},
           {"plane_normalized", json_vector<T, 4>(unit.abcd)},
           {"light", json_vector<T, 4>(light)},
           {"light_type", kind},
           {"p_dot_l", json_number(pl)},
           {"matrix", json_matrix(s)}};
    std::cout << j.dump() << "\n";
    return;
  }
  std::cout << "shadow matrix S = (P.L) I - L P^T, " << layout_name(a.layout) << " layout (" << layout_rule(a.layout)
            << "), " << precision_name<T>() << "\n"
            << "  plane " << text_vector<T, 4>(plane.abcd) << ", normalised " << text_vector<T, 4>(unit.abcd) << "\n"
            << "  light " << text_vector<T, 4>(light) << " (" << kind << "), P.L = " << text_number(pl) << "\n\n"
            << text_matrix(s, a.layout);
}

// ---------------------------------------------------------------- perspective

struct PerspectiveArgs {
  double fovy_deg = 0, aspect = 0, near = 0;
  std::optional<double> far, epsilon;
  bool infinite = false, reversed = false, json = false;
  DepthRange depth = DepthRange::NegOneToOne;
  Handedness hand = Handedness::Right;
  Layout layout = Layout::Canonical;
  Precision precision = Precision::Double;
};

template <class T>
void run_perspective(const PerspectiveArgs& a) {
  if (a.far && a.infinite) throw BadInput("--far and --infinite exclude each other");
  if (a.far && a.epsilon) throw BadInput("--epsilon applies to the infinite far plane only (drop --far)");
  // Name the option that is not finite (1e999, nan, or beyond float with --precision float):
  // mathlib's answer alone ("an input is NaN or infinite") does not say which.
  const std::pair<const char*, std::optional<double>> scalars[] = {
      {"--fovy-deg", a.fovy_deg}, {"--aspect", a.aspect}, {"--near", a.near}, {"--far", a.far}, {"--epsilon", a.epsilon}};
  for (const auto& [option, value] : scalars) {
    if (!value) continue;
    if (!std::isfinite(*value)) throw BadInput(std::string(option) + ": must be a finite number");
    if (!std::isfinite(T(*value))) throw BadInput(std::string(option) + ": must be a finite number in " + precision_name<T>());
  }
  const ClipConvention conv{a.hand, a.depth, a.reversed ? DepthOrder::Reversed : DepthOrder::Standard};
  const T fovy = T(a.fovy_deg * std::numbers::pi / 180.0);
  const T eps = T(a.epsilon.value_or(0.0));
  Result<Mat4<T>> r = a.far ? perspective<T>(fovy, T(a.aspect), T(a.near), T(*a.far), conv)
                            : perspective_infinite<T>(fovy, T(a.aspect), T(a.near), conv, eps);
  Mat4<T> m = require(r, "perspective");
  if (a.layout == Layout::D3dx) m.transposeInPlace();
  if (a.json) {
    json j{{"command", "perspective"},
           {"layout", layout_name(a.layout)},
           {"precision", precision_name<T>()},
           {"fovy_deg", a.fovy_deg},
           {"aspect", a.aspect},
           {"near", a.near},
           {"far", a.far ? json(*a.far) : json(nullptr)},
           {"infinite", !a.far},
           {"epsilon", json_number(eps)},
           {"depth", to_string(a.depth)},
           {"hand", to_string(a.hand)},
           {"reversed", a.reversed},
           {"matrix", json_matrix(m)}};
    std::cout << j.dump() << "\n";
    return;
  }
  std::cout << (a.far ? "perspective" : "infinite perspective") << ", " << to_string(a.hand) << ", "
            << to_string(a.depth) << (a.reversed ? " reversed-Z" : "") << ", " << layout_name(a.layout) << " layout ("
            << layout_rule(a.layout) << "), " << precision_name<T>() << "\n"
            << "  fovy " << format_number(a.fovy_deg) << " deg, aspect " << format_number(a.aspect) << ", near "
            << format_number(a.near) << ", far " << (a.far ? format_number(*a.far) : std::string("infinity"))
            << (a.far ? "" : ", epsilon " + text_number(eps)) << "\n\n"
            << text_matrix(m, a.layout);
}

// ---------------------------------------------------------------- plane

struct PlaneArgs {
  std::vector<std::string> points;
  std::string point, normal;
  bool normalize = false, json = false;
};

void run_plane(const PlaneArgs& a) {
  const bool by_points = !a.points.empty();
  const bool by_normal = !a.point.empty() || !a.normal.empty();
  if (by_points == by_normal) throw BadInput("give either --points P0 P1 P2 or --point P --normal N");
  Plane<double> plane;
  if (by_points) {
    if (a.points.size() != 3) throw BadInput("--points: expected 3 points, got " + std::to_string(a.points.size()));
    Vec3<double> p[3];
    for (int i = 0; i < 3; ++i) {
      const auto v = parse_numbers("--points", a.points[i], 3);
      p[i] = Vec3<double>(v[0], v[1], v[2]);
    }
    plane = require(plane_from_points(p[0], p[1], p[2]), "--points");
  } else {
    if (a.point.empty() || a.normal.empty()) throw BadInput("--point and --normal go together");
    const auto p = parse_numbers("--point", a.point, 3);
    const auto n = parse_numbers("--normal", a.normal, 3);
    plane = require(plane_from_point_normal(Vec3<double>(p[0], p[1], p[2]), Vec3<double>(n[0], n[1], n[2])), "--normal");
  }
  if (a.normalize) plane = require(shadowref::normalize(plane), "plane");
  if (a.json) {
    std::cout << json{{"command", "plane"}, {"normalized", a.normalize}, {"plane", json_vector<double, 4>(plane.abcd)}}.dump()
              << "\n";
    return;
  }
  std::cout << "plane (a, b, c, d): a x + b y + c z + d = 0" << (a.normalize ? ", normalised" : "") << "\n  "
            << text_vector<double, 4>(plane.abcd) << "\n";
}

// An option whose value is one of the names in `map`; the help shows the names and the default.
template <class Value>
void add_enum_option(CLI::App* cmd, const std::string& name, Value& value, const std::map<std::string, Value>& map,
                     const std::string& help) {
  std::string current;
  for (const auto& [k, v] : map)
    if (v == value) current = k;
  cmd->add_option_function<std::string>(
         name, [&value, &map](const std::string& s) { value = map.at(s); }, help + " (default: " + current + ")")
      ->check(CLI::IsMember(map))
      ->type_name("");
}

}  // namespace

void register_math_command(CLI::App& app, int& exit_code) {
  CLI::App* math = app.add_subcommand("math", "The matrix calculator: shadow matrices, projections, planes (canonical or D3DX layout); mesh reports and silhouettes.");
  math->require_subcommand(1);

  {
    auto args = std::make_shared<ShadowMatrixArgs>();
    CLI::App* cmd = math->add_subcommand(
        "shadow-matrix", "The planar shadow matrix S = (P.L) I - L P^T for plane P (normalised by |(a,b,c)|) and light L.");
    cmd->add_option("--plane", args->plane, "plane a,b,c,d with a x + b y + c z + d = 0")->required();
    cmd->add_option("--light", args->light, "light x,y,z,w: w = 1 point light, w = 0 directional (xyz toward the light)")->required();
    add_enum_option(cmd, "--layout", args->layout, kLayouts, "canonical (column vectors) or d3dx (row vectors, the transpose)");
    add_enum_option(cmd, "--precision", args->precision, kPrecisions, "scalar type of the computation");
    cmd->add_flag("--json", args->json, "print one JSON object");
    cmd->callback([args] {
      if (args->precision == Precision::Float) run_shadow_matrix<float>(*args);
      else run_shadow_matrix<double>(*args);
    });
  }
  {
    auto args = std::make_shared<PerspectiveArgs>();
    CLI::App* cmd = math->add_subcommand("perspective", "A perspective projection, finite or infinite, in any handedness and depth range.");
    cmd->add_option("--fovy-deg", args->fovy_deg, "vertical field of view in degrees, in (0, 180)")->required();
    cmd->add_option("--aspect", args->aspect, "width / height, > 0")->required();
    cmd->add_option("--near", args->near, "near plane distance, > 0")->required();
    cmd->add_option("--far", args->far, "far plane distance, > near (default: infinite far plane)");
    cmd->add_flag("--infinite", args->infinite, "far plane at infinity (the default when --far is absent)");
    cmd->add_option("--epsilon", args->epsilon, "Lengyel's epsilon for the infinite far plane, in [0, 1) (default 0)");
    add_enum_option(cmd, "--depth", args->depth, kDepths, "clip-space depth range");
    add_enum_option(cmd, "--hand", args->hand, kHands, "rh looks down -z, lh down +z");
    cmd->add_flag("--reversed", args->reversed, "reversed-Z (near -> 1, far -> 0); needs --depth zero-to-one");
    add_enum_option(cmd, "--layout", args->layout, kLayouts, "canonical (column vectors) or d3dx (row vectors, the transpose)");
    add_enum_option(cmd, "--precision", args->precision, kPrecisions, "scalar type of the computation");
    cmd->add_flag("--json", args->json, "print one JSON object");
    cmd->callback([args] {
      if (args->precision == Precision::Float) run_perspective<float>(*args);
      else run_perspective<double>(*args);
    });
  }
  {
    auto args = std::make_shared<PlaneArgs>();
    CLI::App* cmd = math->add_subcommand("plane", "A plane (a, b, c, d) from three points or from a point and a normal.");
    cmd->add_option("--points", args->points, "three points x,y,z x,y,z x,y,z (normal = (p1-p0) x (p2-p0))")->expected(3);
    cmd->add_option("--point", args->point, "a point x,y,z on the plane");
    cmd->add_option("--normal", args->normal, "the normal x,y,z (any non-zero length)");
    cmd->add_flag("--normalize", args->normalize, "divide by |(a, b, c)|");
    cmd->add_flag("--json", args->json, "print one JSON object");
    cmd->callback([args] { run_plane(*args); });
  }
  register_math_mesh_commands(*math, exit_code);
}

}  // namespace shadowref::cli
