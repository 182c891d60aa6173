// math_mesh_command.cpp — `shadowref math mesh-report` and `shadowref math silhouette`: the mesh
// side of the calculator (edge adjacency and silhouettes from mathlib's adjacency.hpp and
// silhouette.hpp).
//
// Meshes come from scene/'s load_mesh_file (OBJ, glTF), in double, with the file's own vertex
// indices (0-based): the silhouette's edges name vertices of the file, never of a welded copy.
// Every problem with the file (missing, unparsable, an index out of range, NaN coordinates, no
// triangle) is one line on stderr and exit code 4, like every other bad input.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "command.hpp"
#include "numbers.hpp"
#include "shadowref/adjacency.hpp"
#include "shadowref/scene/mesh_file.hpp"
#include "shadowref/silhouette.hpp"
#include "shadowref/outputs/json_text.hpp"

namespace shadowref::cli {
namespace {

using nlohmann::json;

TriangleMesh<double> load_mesh(const std::string& path) {
  try {
    return scene::load_mesh_file(path);
  } catch (const scene::MeshFileError& e) {
    throw BadInput("--mesh '" + path + "': " + e.what());
  }
}

// ---------------------------------------------------------------- mesh-report

struct MeshReportArgs {
  std::string mesh;
  bool json = false;
};

void run_mesh_report(const MeshReportArgs& a) {
  const TriangleMesh<double> mesh = load_mesh(a.mesh);
  const auto adj = build_adjacency(mesh);
  if (!adj) throw BadInput("--mesh '" + a.mesh + "': " + adj.message());
  const MeshReport& r = adj->report;
  if (a.json) {
    std::cout << outputs::json_text(json{{"command", "mesh-report"},
                      {"mesh", a.mesh},
                      {"vertices", r.vertices},
                      {"welded_vertices", r.welded_vertices},
                      {"triangles", r.triangles},
                      {"edges", r.edges},
                      {"open_edges", r.open_edges},
                      {"non_manifold_edges", r.non_manifold_edges},
                      {"miswound_edges", r.miswound_edges},
                      {"degenerate_triangles", r.degenerate_triangles},
                      {"closed_manifold", r.closed_manifold()}}
                     )
              << "\n";
    return;
  }
  std::cout << "mesh " << a.mesh << "\n"
            << "  vertices              " << r.vertices << " (" << r.welded_vertices << " distinct positions used)\n"
            << "  triangles             " << r.triangles << "\n"
            << "  edges                 " << r.edges << " (matched on equal positions)\n"
            << "  open edges            " << r.open_edges << "\n"
            << "  non-manifold edges    " << r.non_manifold_edges << "\n"
            << "  mis-wound edges       " << r.miswound_edges << "\n"
            << "  degenerate triangles  " << r.degenerate_triangles << "\n"
            << "  closed 2-manifold     " << (r.closed_manifold() ? "yes" : "no") << "\n";
}

// ---------------------------------------------------------------- silhouette

struct SilhouetteArgs {
  std::string mesh, light;
  bool json = false;
};

void run_silhouette(const SilhouetteArgs& a) {
  const std::vector<double> l = parse_numbers("--light", a.light, 4);
  const Vec4<double> light(l[0], l[1], l[2], l[3]);
  if (const auto bad = validate_light(light)) throw BadInput(std::string("--light: ") + describe(*bad));
  const auto caster = make_shadow_caster(load_mesh(a.mesh));
  if (!caster) throw BadInput("--mesh '" + a.mesh + "': " + caster.message());
  Silhouette<double> s;
  const auto n = find_silhouette(*caster, light, s);
  if (!n) throw BadInput(std::string("silhouette: ") + n.message());
  const char* kind = light.w() == 0.0 ? "directional" : "point";
  if (a.json) {
    json edges = json::array();
    for (const SilhouetteEdge& e : s.edges) edges.push_back({e.from, e.to});
    json light_json = json::array();
    for (int i = 0; i < 4; ++i) light_json.push_back(light[i] + 0.0);  // -0 prints as 0
    std::cout << outputs::json_text(json{{"command", "silhouette"},
                      {"mesh", a.mesh},
                      {"light", light_json},
                      {"light_type", kind},
                      {"lit_triangles", s.lit_count},
                      {"count", s.edges.size()},
                      {"edges", edges}}
                     )
              << "\n";
    return;
  }
  std::cout << "silhouette of " << a.mesh << " for the " << kind << " light (" << format_number(light[0]) << ", "
            << format_number(light[1]) << ", " << format_number(light[2]) << ", " << format_number(light[3]) << ")\n"
            << "  " << s.lit_count << " lit triangles (plane . L >= 0), " << s.edges.size() << " silhouette edges\n"
            << "  each edge (i, j) is walked opposite to its lit face: the quad i, j, j', i' faces out of the volume\n";
  for (const SilhouetteEdge& e : s.edges) std::cout << "  " << e.from << " " << e.to << "\n";
}

}  // namespace

void register_math_mesh_commands(CLI::App& math, int& exit_code) {
  (void)exit_code;  // these either succeed (0) or throw BadInput (4)
  {
    auto args = std::make_shared<MeshReportArgs>();
    CLI::App* cmd = math.add_subcommand(
        "mesh-report", "Counts of a mesh's vertices, triangles, open, non-manifold and mis-wound edges, and whether it is a closed 2-manifold.");
    cmd->add_option("--mesh", args->mesh, "mesh file (.obj, .gltf, .glb)")->required();
    cmd->add_flag("--json", args->json, "print one JSON object");
    cmd->callback([args] { run_mesh_report(*args); });
  }
  {
    auto args = std::make_shared<SilhouetteArgs>();
    CLI::App* cmd = math.add_subcommand(
        "silhouette", "The silhouette edges of a mesh for a homogeneous light, as vertex index pairs of the file, oriented so the extruded quad faces out of the shadow volume.");
    cmd->add_option("--mesh", args->mesh, "mesh file (.obj, .gltf, .glb)")->required();
    cmd->add_option("--light", args->light, "light x,y,z,w: w = 1 point light, w = 0 directional (xyz toward the light)")->required();
    cmd->add_flag("--json", args->json, "print one JSON object");
    cmd->callback([args] { run_silhouette(*args); });
  }
}

}  // namespace shadowref::cli
