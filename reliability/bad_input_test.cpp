// bad_input_test.cpp — every `shadowref` subcommand answers bad input with one
// line naming the file, JSON path or argument, and the documented exit code (docs/output-contract.md) (4 bad input or file
// error, 3 size mismatch); never a crash, a hang, a partial output folder.
//
// The table is generated: each defect (a bad scene, mesh, image or argument) × each subcommand that
// reads that kind of input. Bad files are written at test time into a fresh folder per case. A case
// passes when
//   - the exit code is the expected one (a signal, a sanitizer abort or the 120 s watchdog fail it),
//   - the last stderr line starts with "shadowref <subcommand>" and names what `must_mention` says
//     (the file, the JSON path or the argument), and every earlier stderr line is progress
//     (cases whose failure comes before any work demand exactly one line),
//   - stdout is empty,
//   - the case's output folder does not exist afterwards (nothing left looking complete).
#include <gtest/gtest.h>

#include <zlib.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "run_command.hpp"

namespace shadowref::test {
namespace {

namespace fs = std::filesystem;

// ------------------------------------------------------------------------------------ fixtures

// A valid scene, small and fast: a box over a ground plane, 32 × 32 pixels.
std::string good_scene(const std::string& patch_key = "", const std::string& patch_value = "") {
  std::string name = R"("bad")", res = "[32, 32]", camera = R"({"position": [0, 4, 8], "target": [0, 0.5, 0], "fovy_deg": 45, "near": 0.1})",
              lights = R"([{"type": "point", "position": [2, 6, 1]}])",
              objects = R"([{"name": "ground", "shape": {"type": "plane", "size": [20, 20]}, "receiver": true},
                 {"name": "box", "shape": {"type": "box", "size": [1, 1, 1]}, "transform": {"translate": [0, 1, 0]}}])",
              extra;
  if (patch_key == "name") name = patch_value;
  else if (patch_key == "resolution") res = patch_value;
  else if (patch_key == "camera") camera = patch_value;
  else if (patch_key == "lights") lights = patch_value;
  else if (patch_key == "objects") objects = patch_value;
  else if (!patch_key.empty()) extra = ", \"" + patch_key + "\": " + patch_value;
  return R"({"name": )" + name + R"(, "resolution": )" + res + ", \"camera\": " + camera + ", \"lights\": " + lights +
         ", \"objects\": " + objects + extra + "}";
}

std::string mesh_object(const std::string& file) {
  return R"([{"name": "ground", "shape": {"type": "plane", "size": [20, 20]}, "receiver": true},
            {"name": "part", "shape": {"type": "mesh", "file": ")" + file + R"("}}])";
}

void write_text(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << text;
}

// A PNG chunk: length, type, data, and the CRC of type and data (zlib's crc32).
void append_chunk(std::string& png, const char* type, const std::string& data) {
  const auto be32 = [&](std::uint32_t v) {
    for (int s = 24; s >= 0; s -= 8) png.push_back(static_cast<char>((v >> s) & 0xff));
  };
  be32(static_cast<std::uint32_t>(data.size()));
  const std::string body = type + data;
  png += body;
  be32(static_cast<std::uint32_t>(crc32(0, reinterpret_cast<const Bytef*>(body.data()), static_cast<uInt>(body.size()))));
}

// A w x h PNG of `channels` channels (1 grey, 3 RGB) whose every sample is `value`, 8 or 16 bits
// deep, encoded here (zlib deflates the rows) so that this test's inputs do not come from the code
// under test and the test does not load OpenImageIO.
void write_png(const fs::path& p, int w, int h, int channels, std::uint8_t value, int bits = 8) {
  fs::create_directories(p.parent_path());
  const std::size_t row = 1 + static_cast<std::size_t>(w) * static_cast<std::size_t>(channels) * (bits / 8);
  std::string raw;
  raw.reserve(row * static_cast<std::size_t>(h));
  for (int y = 0; y < h; ++y) {
    raw.push_back('\0');  // filter: none
    raw.append(row - 1, static_cast<char>(value));  // 16-bit: value * 257, both bytes alike
  }
  uLongf size = compressBound(static_cast<uLong>(raw.size()));
  std::string deflated(size, '\0');
  ASSERT_EQ(compress2(reinterpret_cast<Bytef*>(deflated.data()), &size, reinterpret_cast<const Bytef*>(raw.data()),
                      static_cast<uLong>(raw.size()), 9), Z_OK);
  deflated.resize(size);
  std::string ihdr;
  for (int v : {w, h})
    for (int s = 24; s >= 0; s -= 8) ihdr.push_back(static_cast<char>((static_cast<std::uint32_t>(v) >> s) & 0xff));
  ihdr += {static_cast<char>(bits), static_cast<char>(channels == 3 ? 2 : 0), 0, 0, 0};
  std::string png = "\x89PNG\r\n\x1a\n";
  append_chunk(png, "IHDR", ihdr);
  append_chunk(png, "IDAT", deflated);
  append_chunk(png, "IEND", "");
  std::ofstream(p, std::ios::binary) << png;
}

// A mask folder as every producer writes it: mask.png (+ decided.png for a reference).
void write_mask_folder(const fs::path& dir, int w, int h, bool reference) {
  write_png(dir / "mask.png", w, h, 1, 255);
  if (reference) write_png(dir / "decided.png", w, h, 1, 255);
}

// A glTF holding one triangle, its positions in buffer `uri`; `diamond` > 0 puts the mesh under a
// chain of that many nodes, each naming the next one twice (2^diamond instances of the mesh).
constexpr const char* kTriangleDataUri =
    "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA";
std::string gltf_triangle(const std::string& uri, int diamond = 0, const std::string& byte_length = "36") {
  std::string nodes;
  for (int i = 0; i < diamond; ++i)
    nodes += "{\"children\": [" + std::to_string(i + 1) + ", " + std::to_string(i + 1) + "]}, ";
  nodes += R"({"mesh": 0})";
  return R"({"asset": {"version": "2.0"}, "buffers": [{"uri": ")" + uri + R"(", "byteLength": )" + byte_length +
         R"(}], "bufferViews": [{"buffer": 0, "byteLength": 36}], "accessors": [{"bufferView": 0, "componentType": 5126,
         "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}], "meshes": [{"primitives": [{"attributes":
         {"POSITION": 0}}]}], "nodes": [)" + nodes + R"(], "scenes": [{"nodes": [0]}]})";
}

// A glTF scene (a camera, a KHR_lights_punctual point light, one triangle) whose primitive is
// compressed by `required` as an exporter writes one, named in extensionsRequired: an extension the
// suite does not read. As a .glb with `binary` (the JSON chunk alone, its buffer a data URI).
std::string gltf_scene_requiring(const std::string& required, bool binary = false) {
  std::string json = R"({"asset": {"version": "2.0"}, "extensionsUsed": ["KHR_lights_punctual", ")" + required +
                     R"("], "extensionsRequired": [")" + required + R"("], "extensions": {"KHR_lights_punctual": {"lights":
      [{"type": "point"}]}}, "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}],
      "buffers": [{"uri": ")" + std::string(kTriangleDataUri) + R"(", "byteLength": 36}], "bufferViews": [{"buffer": 0,
      "byteLength": 36}], "accessors": [{"componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0],
      "max": [1, 1, 0]}], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "extensions": {")" + required +
                     R"(": {"bufferView": 0, "attributes": {"POSITION": 0}}}}]}], "nodes": [{"camera": 0, "translation": [0, 0, 5]},
      {"translation": [0, 3, 3], "extensions": {"KHR_lights_punctual": {"light": 0}}}, {"mesh": 0}],
      "scenes": [{"nodes": [0, 1, 2]}]})";
  if (!binary) return json;
  json.append((4 - json.size() % 4) % 4, ' ');
  std::string glb;
  const auto le32 = [&](std::uint32_t v) {
    for (int s = 0; s < 32; s += 8) glb.push_back(static_cast<char>((v >> s) & 0xff));
  };
  glb += "glTF";
  le32(2);
  le32(static_cast<std::uint32_t>(12 + 8 + json.size()));
  le32(static_cast<std::uint32_t>(json.size()));
  glb += "JSON" + json;
  return glb;
}

// A PNG header (signature + IHDR with a correct CRC) claiming w × h 8-bit grey, and no pixel data.
std::string png_header_only(std::uint32_t w, std::uint32_t h) {
  std::string ihdr = "IHDR";
  for (std::uint32_t v : {w, h})
    for (int s = 24; s >= 0; s -= 8) ihdr.push_back(static_cast<char>((v >> s) & 0xff));
  ihdr += std::string("\x08\x00\x00\x00\x00", 5);
  std::uint32_t crc = 0xffffffffu;
  for (unsigned char c : ihdr) {
    crc ^= c;
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  crc ^= 0xffffffffu;
  std::string png = "\x89PNG\r\n\x1a\n";
  png += std::string("\x00\x00\x00\x0d", 4) + ihdr;
  for (int s = 24; s >= 0; s -= 8) png.push_back(static_cast<char>((crc >> s) & 0xff));
  return png;
}

// ------------------------------------------------------------------------------------ the table

struct Case {
  std::string name;                                  // "<defect>_<subcommand>"
  std::function<void(const fs::path& dir)> setup;    // writes the bad files under dir
  std::vector<std::string> args;                     // "@" is replaced by the case's folder
  int exit_code = 4;
  std::string must_mention;                          // "@" replaced too
  bool one_line = true;                              // false: progress lines may precede the error
  std::string known_bug = {};                        // non-empty: an expected failure (XFAIL), reported to
                                                     // the code's owner; passing then fails (XPASS)
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

std::string expand(std::string s, const fs::path& dir) {
  for (std::size_t at; (at = s.find('@')) != std::string::npos;) s.replace(at, 1, dir.string());
  return s;
}

// The subcommands that read a scene file, as argv for a scene at `@/scene.json` (or a catalogue
// folder `@/cat` holding it), each writing into @/out.
struct SceneReader {
  std::string name;
  std::vector<std::string> args;
  bool catalogue;  // reads a folder of scenes (scene written to @/cat/scene.json)
};

const std::vector<SceneReader>& scene_readers() {
  static const std::vector<SceneReader> r = {
      {"render", {"render", "--scene", "@/scene.json", "--technique", "planar", "--out", "@/out"}, false},
      {"reference", {"reference", "--scene", "@/scene.json", "--out", "@/out", "--spp", "1"}, false},
      {"conform", {"conform", "--catalogue", "@/cat", "--out", "@/out", "--quiet", "--spp", "1"}, true},
      {"export", {"export", "--catalogue", "@/cat", "--out", "@/out"}, true},
      {"goldens", {"goldens", "--check", "--catalogue", "@/cat", "--dir", "@/out"}, true},
  };
  return r;
}

// A defective scene (and what the message must name, relative to the scene file).
struct SceneDefect {
  std::string name;
  std::function<void(const fs::path& scene_dir)> extra_files;  // meshes next to the scene
  std::string text;
  std::string must_mention;  // in addition to the scene file's name
};

const std::vector<SceneDefect>& scene_defects() {
  static const std::vector<SceneDefect> d = {
      {"malformed_json", nullptr, R"({"name": "bad", "resolution": [32, 32], "camera": )", "invalid JSON"},
      {"wrong_type", nullptr, good_scene("resolution", R"("large")"), "resolution"},
      {"wrong_type_nested", nullptr, good_scene("lights", R"([{"type": "point", "position": "up"}])"), "lights[0].position"},
      {"out_of_range", nullptr, good_scene("camera", R"({"position": [0, 4, 8], "target": [0, 0, 0], "fovy_deg": 200})"),
       "camera.fovy_deg"},
      {"infinite_number", nullptr, good_scene("lights", R"([{"type": "point", "position": [1e999, 6, 1]}])"), "invalid JSON"},
      {"unknown_key", nullptr, good_scene("colour", "1"), "colour"},
      {"resolution_zero", nullptr, good_scene("resolution", "[0, 32]"), "resolution[0]"},
      {"resolution_huge", nullptr, good_scene("resolution", "[32, 1000000000]"), "resolution[1]"},
      {"unknown_expect_technique", nullptr, good_scene("expect", R"({"planer": {"result": "pass"}})"), "expect.planer"},
      {"obj_nan_vertex", [](const fs::path& dir) { write_text(dir / "nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n"); },
       good_scene("objects", mesh_object("nan.obj")), "vertex 2 is NaN or infinite"},
      {"obj_inf_vertex", [](const fs::path& dir) { write_text(dir / "inf.obj", "v 0 0 0\nv 1 -inf 0\nv 0 1 0\nf 1 2 3\n"); },
       good_scene("objects", mesh_object("inf.obj")), "vertex 2 is NaN or infinite"},
      {"obj_index_out_of_range",
       [](const fs::path& dir) { write_text(dir / "idx.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"); },
       good_scene("objects", mesh_object("idx.obj")), "uses vertex 9"},
      {"obj_negative_index",
       [](const fs::path& dir) { write_text(dir / "neg.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -7\n"); },
       good_scene("objects", mesh_object("neg.obj")), "objects[1].shape.file"},
      {"empty_mesh", [](const fs::path& dir) { write_text(dir / "empty.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"); },
       good_scene("objects", mesh_object("empty.obj")), "no triangles"},
      {"missing_mesh", nullptr, good_scene("objects", mesh_object("nowhere.obj")), "nowhere.obj"},
      {"truncated_gltf", [](const fs::path& dir) { write_text(dir / "cut.gltf", R"({"asset": {"version": "2.0"}, "meshes": [)"); },
       good_scene("objects", mesh_object("cut.gltf")), "cut.gltf"},
      // glTF: an external buffer outside the glTF file's folder is not read; a hierarchy naming one
      // node many times over (2^60 instances) and a buffer claiming a terabyte are refused.
      {"gltf_buffer_climbs_out", [](const fs::path& dir) { write_text(dir / "m.gltf", gltf_triangle("../outside.bin")); },
       good_scene("objects", mesh_object("m.gltf")), "is outside the glTF file's folder"},
      {"gltf_buffer_absolute", [](const fs::path& dir) { write_text(dir / "m.gltf", gltf_triangle("/etc/passwd")); },
       good_scene("objects", mesh_object("m.gltf")), "is outside the glTF file's folder"},
      {"gltf_exponential_hierarchy", [](const fs::path& dir) { write_text(dir / "m.gltf", gltf_triangle(kTriangleDataUri, 60)); },
       good_scene("objects", mesh_object("m.gltf")), "the node hierarchy instances more than"},
      {"gltf_huge_buffer",
       [](const fs::path& dir) { write_text(dir / "m.gltf", gltf_triangle(kTriangleDataUri, 0, "1000000000000")); },
       good_scene("objects", mesh_object("m.gltf")), "m.gltf"},
      // A scene's name becomes a folder name (renders/<name>/, the reference cache's <name>-<key>/):
      // only safe identifiers (shadowref/scene/identifier.hpp).
      {"name_climbs_out", nullptr, good_scene("name", R"("../../escaped_scene")"), "name: must not contain '..'"},
      {"name_with_slash", nullptr, good_scene("name", R"("a/b")"), "name: must not contain '/'"},
      {"name_with_drive", nullptr, good_scene("name", R"("C:evil")"), "name: must not contain ':'"},
      {"name_hidden", nullptr, good_scene("name", R"(".hidden")"), "name: must start with a letter or a digit, not '.'"},
      {"name_empty", nullptr, good_scene("name", R"("")"), "name: must not be empty"},
      {"name_too_long", nullptr, good_scene("name", "\"" + std::string(65, 'a') + "\""), "name: must be at most 64 characters, not 65"},
      // Mesh files lie in the scene's folder or below it.
      {"mesh_absolute_path", nullptr, good_scene("objects", mesh_object("/etc/passwd")),
       "objects[1].shape.file: '/etc/passwd' is an absolute path, outside the scene's folder"},
      {"mesh_climbs_out", nullptr, good_scene("objects", mesh_object("../outside.obj")),
       "objects[1].shape.file: '../outside.obj' resolves to"},
  };
  return d;
}

std::vector<Case> make_cases() {
  std::vector<Case> cases;
  // Scene defects × every subcommand that reads scenes.
  for (const SceneReader& r : scene_readers()) {
    cases.push_back({"missing_file_" + r.name, nullptr,
                     r.catalogue ? std::vector<std::string>{} : r.args, 4, "@/scene.json"});
    if (r.catalogue) {  // a catalogue folder that does not exist
      cases.back().args = r.args;
      cases.back().must_mention = "@/cat";
    }
    for (const SceneDefect& d : scene_defects()) {
      const std::string scene_name = r.catalogue ? "@/cat/scene.json" : "@/scene.json";
      const auto extra = d.extra_files;
      const std::string text = d.text;
      const bool cat = r.catalogue;
      cases.push_back({d.name + "_" + r.name,
                       [extra, text, cat](const fs::path& dir) {
                         const fs::path sdir = cat ? dir / "cat" : dir;
                         write_text(sdir / "scene.json", text);
                         if (extra) extra(sdir);
                       },
                       r.args, 4, d.must_mention});
      cases.push_back(cases.back());  // and the file name, separately
      cases.back().name += "_names_file";
      cases.back().must_mention = scene_name;
    }
  }
  const std::string good = good_scene();
  const auto good_scene_file = [good](const fs::path& dir) { write_text(dir / "scene.json", good); };
  const auto blocked_out = [good](const fs::path& dir) {  // --out below a regular file
    write_text(dir / "scene.json", good);
    write_text(dir / "file", "not a folder");
  };

  // render: arguments.
  const std::vector<std::string> render = {"render", "--scene", "@/scene.json", "--out", "@/out"};
  const auto with = [](std::vector<std::string> a, std::initializer_list<std::string> more) {
    a.insert(a.end(), more);
    return a;
  };
  cases.push_back({"unknown_technique_render", good_scene_file, with(render, {"--technique", "planer"}), 4, "--technique"});
  cases.push_back({"unknown_backend_render", good_scene_file, with(render, {"--technique", "planar", "--backend", "vulkan"}), 4, "vulkan"});
  cases.push_back({"unknown_gl_render", good_scene_file, with(render, {"--technique", "planar", "--gl", "glx"}), 4, "glx"});
  cases.push_back({"shadow_map_size_huge_render", good_scene_file,
                   with(render, {"--technique", "shadowmap", "--shadow-map-size", "1000000"}), 4, "--shadow-map-size"});
  cases.push_back({"frames_zero_render", good_scene_file, with(render, {"--technique", "planar", "--frames", "0"}), 4, "--frames"});
  cases.push_back({"missing_argument_render", good_scene_file, {"render", "--scene", "@/scene.json", "--out", "@/out"}, 4, "--technique"});
  cases.push_back({"unwritable_out_render", blocked_out,
                   {"render", "--scene", "@/scene.json", "--technique", "planar", "--out", "@/file/out"}, 4, "@/file", false});

  // reference: arguments.
  const std::vector<std::string> reference = {"reference", "--scene", "@/scene.json", "--out", "@/out"};
  cases.push_back({"spp_not_square_reference", good_scene_file, with(reference, {"--spp", "3"}), 4, "--spp"});
  cases.push_back({"spp_huge_reference", good_scene_file, with(reference, {"--spp", "1000000"}), 4, "--spp"});
  cases.push_back({"threads_negative_reference", good_scene_file, with(reference, {"--threads", "-1"}), 4, "--threads"});
  cases.push_back({"not_a_number_reference", good_scene_file, with(reference, {"--spp", "many"}), 4, "--spp"});
  cases.push_back({"unwritable_out_reference", blocked_out,
                   {"reference", "--scene", "@/scene.json", "--spp", "1", "--out", "@/file/out"}, 4, "@/file", false});

  // compare: images.
  const std::vector<std::string> compare = {"compare", "--reference", "@/ref", "--candidate", "@/cand"};
  const auto ref_ok = [](const fs::path& dir) { write_mask_folder(dir / "ref", 16, 16, true); };
  cases.push_back({"missing_file_compare", [](const fs::path&) {}, compare, 4, "@/ref"});
  cases.push_back({"missing_candidate_compare", ref_ok, compare, 4, "@/cand"});
  cases.push_back({"truncated_image_compare",
                   [ref_ok](const fs::path& dir) {
                     ref_ok(dir);
                     write_mask_folder(dir / "cand", 16, 16, false);
                     const fs::path m = dir / "cand" / "mask.png";
                     const auto size = fs::file_size(m);
                     fs::resize_file(m, size / 2);
                   },
                   compare, 4, "@/cand/mask.png"});
  // Cut inside the pixel data of a larger image: the error surfaces in read_image, not at open,
  // and OpenImageIO's message there has three lines (its own, its PNG reader's, libpng's).
  cases.push_back({"truncated_in_pixels_compare",
                   [](const fs::path& dir) {
                     write_mask_folder(dir / "ref", 256, 256, true);
                     write_mask_folder(dir / "cand", 256, 256, false);
                     const fs::path m = dir / "cand" / "mask.png";
                     fs::resize_file(m, fs::file_size(m) * 3 / 4);
                   },
                   compare, 4, "@/cand/mask.png"});
  cases.push_back({"empty_image_compare",
                   [ref_ok](const fs::path& dir) {
                     ref_ok(dir);
                     write_text(dir / "cand" / "mask.png", "");
                   },
                   compare, 4, "@/cand/mask.png"});
  cases.push_back({"text_as_image_compare",
                   [ref_ok](const fs::path& dir) {
                     ref_ok(dir);
                     write_text(dir / "cand" / "mask.png", "this is not a PNG\n");
                   },
                   compare, 4, "@/cand/mask.png"});
  cases.push_back({"rgb_mask_compare",
                   [ref_ok](const fs::path& dir) {
                     ref_ok(dir);
                     write_png(dir / "cand" / "mask.png", 16, 16, 3, 255);
                   },
                   compare, 4, "channel"});
  // A technique name that would climb out of --out (it becomes a folder name) is refused.
  cases.push_back({"technique_climbs_out_conform", [](const fs::path& dir) { fs::create_directories(dir / "cand"); },
                   {"conform", "--candidate-dir", "@/cand", "--technique", "../../escaped", "--out", "@/out"}, 4,
                   "--technique '../../escaped'"});
  // Mask values other than 255 / 0 / 128 are refused, not rounded (a mask written as 10 / 250).
  cases.push_back({"off_values_mask_compare",
                   [ref_ok](const fs::path& dir) {
                     ref_ok(dir);
                     write_png(dir / "cand" / "mask.png", 16, 16, 1, 250);
                   },
                   compare, 4, "256 pixel(s) hold values other than 255 (lit), 0 (shadowed) and 128"});
  cases.push_back({"sixteen_bit_mask_compare",
                   [ref_ok](const fs::path& dir) {
                     ref_ok(dir);
                     write_png(dir / "cand" / "mask.png", 16, 16, 1, 255, 16);
                   },
                   compare, 4, "8-bit"});
  cases.push_back({"absurd_header_compare",
                   [ref_ok](const fs::path& dir) {
                     ref_ok(dir);
                     write_text(dir / "cand" / "mask.png", png_header_only(1000000, 1000000));
                   },
                   compare, 4, "@/cand/mask.png"});
  cases.push_back({"absurd_header_reference_compare",
                   [](const fs::path& dir) {
                     write_mask_folder(dir / "cand", 16, 16, false);
                     write_mask_folder(dir / "ref", 16, 16, true);
                     write_text(dir / "ref" / "decided.png", png_header_only(1000000, 1000000));
                   },
                   compare, 4, "@/ref/decided.png"});
  cases.push_back({"size_mismatch_compare",
                   [ref_ok](const fs::path& dir) {
                     ref_ok(dir);
                     write_mask_folder(dir / "cand", 8, 16, false);
                   },
                   compare, 3, "size mismatch"});
  cases.push_back({"decided_size_mismatch_compare",
                   [](const fs::path& dir) {
                     write_mask_folder(dir / "ref", 16, 16, false);
                     write_png(dir / "ref" / "decided.png", 16, 15, 1, 255);
                     write_mask_folder(dir / "cand", 16, 16, false);
                   },
                   compare, 3, "size mismatch"});
  cases.push_back({"unknown_technique_compare",
                   [ref_ok](const fs::path& dir) {
                     ref_ok(dir);
                     write_mask_folder(dir / "cand", 16, 16, false);
                   },
                   with(compare, {"--technique", "planer"}), 4, "planer"});

  // conform: arguments.
  const std::vector<std::string> conform = {"conform", "--catalogue", "@/cat", "--out", "@/out", "--quiet"};
  const auto good_catalogue = [good](const fs::path& dir) { write_text(dir / "cat" / "scene.json", good); };
  cases.push_back({"unknown_technique_conform", good_catalogue, with(conform, {"--techniques", "planer"}), 4, "planer"});
  cases.push_back({"unknown_backend_conform", good_catalogue, with(conform, {"--backend", "vulkan"}), 4, "vulkan"});
  cases.push_back({"unknown_scene_conform", good_catalogue, with(conform, {"--scenes", "no_such_scene"}), 4, "no_such_scene"});
  cases.push_back({"spp_not_square_conform", good_catalogue, with(conform, {"--spp", "3"}), 4, "--spp"});
  cases.push_back({"missing_candidate_dir_conform", good_catalogue, with(conform, {"--candidate-dir", "@/nowhere"}), 4,
                   "@/nowhere"});
  // An engine team's level compressed by its exporter (Draco, meshopt): a feature the suite does not read
  // is one line naming it, as a scene (.gltf, .glb) and as a JSON scene's mesh file.
  cases.push_back({"draco_required_gltf_scene_conform",
                   [](const fs::path& dir) { write_text(dir / "level.gltf", gltf_scene_requiring("KHR_draco_mesh_compression")); },
                   {"conform", "--scenes", "@/level.gltf", "--out", "@/out", "--quiet"}, 4, "KHR_draco_mesh_compression"});
  cases.push_back({"meshopt_required_glb_scene_reference",
                   [](const fs::path& dir) { write_text(dir / "level.glb", gltf_scene_requiring("EXT_meshopt_compression", true)); },
                   {"reference", "--scene", "@/level.glb", "--out", "@/out"}, 4, "EXT_meshopt_compression"});
  cases.push_back({"draco_required_mesh_file_conform",
                   [](const fs::path& dir) {
                     write_text(dir / "cat" / "draco.gltf", gltf_scene_requiring("KHR_draco_mesh_compression"));
                     write_text(dir / "cat" / "scene.json", good_scene("objects", mesh_object("draco.gltf")));
                   },
                   conform, 4, "KHR_draco_mesh_compression"});

  // conform, compare, merge: an engine team's expectations files and shards (docs/ci.md).
  const auto expectations = [good](const std::string& text) {
    return [good, text](const fs::path& dir) {
      write_text(dir / "cat" / "scene.json", good);
      write_text(dir / "fails.txt", text);
    };
  };
  cases.push_back({"bad_status_expectations_conform", expectations("# bug 1\nscene@planar,BROKEN\n"),
                   with(conform, {"--expectations", "@/fails.txt"}), 4, "@/fails.txt:2: unknown status 'BROKEN'"});
  cases.push_back({"bad_line_expectations_conform", expectations("scene@planar\n"), with(conform, {"--expectations", "@/fails.txt"}),
                   4, "@/fails.txt:1"});
  cases.push_back({"bad_regex_expectations_conform", expectations("[flakes]\n(scene\n"),
                   with(conform, {"--expectations", "@/fails.txt"}), 4, "@/fails.txt:2: bad regex"});
  cases.push_back({"missing_expectations_conform", good_catalogue, with(conform, {"--expectations", "@/nowhere.txt"}), 4,
                   "@/nowhere.txt"});
  cases.push_back({"expectations_without_scene_compare",
                   [ref_ok](const fs::path& dir) {
                     ref_ok(dir);
                     write_mask_folder(dir / "cand", 16, 16, false);
                     write_text(dir / "fails.txt", "scene@planar,FAIL\n");
                   },
                   with(compare, {"--expectations", "@/fails.txt"}), 4, "--scene"});
  cases.push_back({"bad_shard_conform", good_catalogue, with(conform, {"--shard", "5/4"}), 4, "--shard '5/4'"});
  cases.push_back({"bad_shard_weights_conform",
                   [good](const fs::path& dir) {
                     write_text(dir / "cat" / "scene.json", good);
                     write_text(dir / "weights.json", "{\"cases\": [{\"scene\": 1}]}");
                   },
                   with(conform, {"--shard", "1/2", "--shard-weights", "@/weights.json"}), 4, "@/weights.json: cases[0]"});
  cases.push_back({"missing_shard_merge", nullptr, {"merge", "@/shard-1", "--out", "@/out"}, 4, "@/shard-1/report.json"});
  // A shard's case is read through its record: a status outside the table is refused with its path.
  cases.push_back({"bad_case_status_merge",
                   [](const fs::path& dir) {
                     write_text(dir / "shard-1" / "report.json",
                                R"({"plan": {}, "cases": [{"scene": "s", "technique": "planar", "status": "MAYBE"}]})");
                   },
                   {"merge", "@/shard-1", "--out", "@/out"}, 4, "@/shard-1/report.json: cases[0].status: \"MAYBE\" is not a status"});
  // What the page shows of a shard's case is read through its record too: a count of the wrong type,
  // and a candidate declaration no candidate.json could state, each refused with its path.
  cases.push_back({"bad_case_count_merge",
                   [](const fs::path& dir) {
                     write_text(dir / "shard-1" / "report.json",
                                R"({"plan": {}, "cases": [{"scene": "s", "technique": "planar", "status": "PASS",
                                    "comparison": {"total": {"wrong": 1, "unexplained": 0, "false_shadow": -1}}}]})");
                   },
                   {"merge", "@/shard-1", "--out", "@/out"}, 4,
                   "@/shard-1/report.json: cases[0].comparison.total.false_shadow: must be a whole number >= 0, not -1"});
  cases.push_back({"bad_case_candidate_merge",
                   [](const fs::path& dir) {
                     write_text(dir / "shard-1" / "report.json",
                                R"({"plan": {}, "cases": [{"scene": "s", "technique": "planar", "status": "PASS",
                                    "candidate": {"lights": "all"}}]})");
                   },
                   {"merge", "@/shard-1", "--out", "@/out"}, 4, "@/shard-1/report.json: cases[0].candidate: lights: must be an array"});
  // A shard number is checked before use: a float is never cast out of range.
  cases.push_back({"bad_shard_number_merge",
                   [](const fs::path& dir) {
                     write_text(dir / "shard-1" / "report.json", R"({"plan": {"shards": 1e300}, "cases": []})");
                   },
                   {"merge", "@/shard-1", "--out", "@/out"}, 4,
                   "@/shard-1/report.json: plan.shards: must be a whole number from 1 to 2147483647, not 1e+300"});
  // diff: two finished runs' report.json, each field checked before use.
  cases.push_back({"missing_report_diff", nullptr, {"diff", "@/run-a", "@/run-b", "--out", "@/out"}, 4, "@/run-a/report.json"});
  cases.push_back({"bad_case_diff",
                   [](const fs::path& dir) { write_text(dir / "run-a" / "report.json", R"({"plan": {}, "cases": [{"scene": "s"}]})"); },
                   {"diff", "@/run-a", "@/run-a", "--out", "@/out"}, 4, "@/run-a/report.json: cases[0].technique"});
  cases.push_back({"escaping_image_diff",
                   [](const fs::path& dir) {
                     write_text(dir / "run-a" / "report.json",
                                R"({"plan": {}, "cases": [{"scene": "s", "technique": "planar", "status": "PASS",
                                    "lights": [{"mask": "mask.png", "candidate": "../../../etc/passwd"}]}]})");
                   },
                   {"diff", "@/run-a", "@/run-a", "--out", "@/out"}, 4, "cases[0].lights[0].candidate: '../../../etc/passwd' leaves"});

  // export / goldens: arguments.
  cases.push_back({"unknown_scene_export", good_catalogue, {"export", "--catalogue", "@/cat", "--out", "@/out", "--scenes", "nope"}, 4, "nope"});
  cases.push_back({"jobs_negative_export", good_catalogue, {"export", "--catalogue", "@/cat", "--out", "@/out", "--jobs", "-1"}, 4, "--jobs"});
  cases.push_back({"check_and_update_goldens", good_catalogue,
                   {"goldens", "--check", "--update", "--catalogue", "@/cat", "--dir", "@/out"}, 4, "--check"});
  cases.push_back({"unknown_scene_goldens", good_catalogue, {"goldens", "--check", "--catalogue", "@/cat", "--dir", "@/out", "--scenes", "nope"}, 4, "nope"});

  // math: arguments and mesh files.
  cases.push_back({"nan_argument_math", nullptr, {"math", "shadow-matrix", "--plane", "0,1,0,0", "--light", "nan,5,0,1"}, 4, "--light"});
  cases.push_back({"infinite_argument_math", nullptr, {"math", "shadow-matrix", "--plane", "0,inf,0,0", "--light", "0,5,0,1"}, 4, "--plane"});
  cases.push_back({"overflow_argument_math", nullptr, {"math", "perspective", "--fovy-deg", "60", "--aspect", "1e999", "--near", "1"}, 4, "--aspect"});
  cases.push_back({"out_of_range_math", nullptr, {"math", "perspective", "--fovy-deg", "60", "--aspect", "1", "--near", "-1"}, 4, "near"});
  cases.push_back({"unknown_layout_math", nullptr, {"math", "shadow-matrix", "--plane", "0,1,0,0", "--light", "0,5,0,1", "--layout", "colmajor"}, 4, "--layout"});
  for (const std::string sub : {"mesh-report", "silhouette"}) {
    std::vector<std::string> base = {"math", sub, "--mesh"};
    const auto mesh_case = [&](const std::string& defect, const std::string& file, const std::string& text, const std::string& mention) {
      std::vector<std::string> a = base;
      a.push_back("@/" + file);
      if (sub == "silhouette") a.insert(a.end(), {"--light", "0,5,0,1"});
      cases.push_back({defect + "_math_" + sub,
                       text.empty() ? std::function<void(const fs::path&)>([](const fs::path&) {})
                                    : std::function<void(const fs::path&)>([file, text](const fs::path& dir) { write_text(dir / file, text); }),
                       a, 4, mention});
    };
    mesh_case("missing_file", "none.obj", "", "no such file");
    mesh_case("obj_nan_vertex", "nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", "vertex 2 is NaN or infinite");
    mesh_case("obj_inf_vertex", "inf.obj", "v 0 0 0\nv 0 0 0\nv 0 1 INF\nf 1 2 3\n", "vertex 3 is NaN or infinite");
    mesh_case("obj_overflow_vertex", "big.obj", "v 0 0 0\nv 1e999 0 0\nv 0 1 0\nf 1 2 3\n", "vertex 2 is NaN or infinite");
    mesh_case("obj_missing_coordinate", "short.obj", "v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n", "vertex 2 has fewer than 3");
    mesh_case("obj_garbage_coordinate", "junk.obj", "v 0 0 0\nv 1 zero 0\nv 0 1 0\nf 1 2 3\n", "'zero'");
    mesh_case("obj_index_out_of_range", "idx.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "uses vertex 4");
    mesh_case("obj_index_zero", "zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "--mesh");
    mesh_case("empty_mesh", "empty.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n", "no triangles");
    mesh_case("empty_file", "nothing.obj", "\n", "no triangles");
    mesh_case("truncated_gltf", "cut.gltf", R"({"asset": {"version": "2.0"}, "buffers": [{"byteLength": 12)", "cut.gltf");
    mesh_case("binary_garbage_glb", "junk.glb", std::string("glTF\x02\x00\x00\x00\xff\xff\xff\x7f", 12), "junk.glb");
    mesh_case("unknown_format", "mesh.ply", "ply\n", "unknown mesh format");
  }

  return cases;
}

// ------------------------------------------------------------------------------------ the test

class BadInput : public ::testing::TestWithParam<Case> {};

TEST_P(BadInput, OneLineNamedAndTheDesignExitCode) {
  const Case& c = GetParam();
  const fs::path dir = fs::path(::testing::TempDir()) / ("shadowref-bad-input-" + c.name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  if (c.setup) c.setup(dir);
  // The watchdog turns a hang into exit 124 (a failure with its own message).
  std::vector<std::string> argv = {"/usr/bin/timeout", "120", SHADOWREF_EXE};
  for (const std::string& a : c.args) argv.push_back(expand(a, dir));
  std::string cmdline;
  for (std::size_t i = 2; i < argv.size(); ++i) cmdline += argv[i] + " ";
  const CommandResult r = run_command(argv);
  ASSERT_NE(r.exit_code, 124) << cmdline << "\nhung (killed after 120 s)";
  // Every check adds to `problems`, so that a known bug can be an expected failure as a whole.
  std::vector<std::string> problems;
  const auto check = [&](bool ok, const std::string& what) {
    if (!ok) problems.push_back(what);
  };
  check(r.exit_code == c.exit_code, "exit code " + std::to_string(r.exit_code) + ", expected " + std::to_string(c.exit_code));
  check(r.out.empty(), "stdout is not empty: " + r.out.substr(0, 200));
  check(!r.err.empty() && r.err.back() == '\n', "stderr is empty or does not end with a newline");
  const auto lines = std::count(r.err.begin(), r.err.end(), '\n');
  if (c.one_line) check(lines == 1, std::to_string(lines) + " lines on stderr, expected one");
  std::string last = r.err.empty() ? r.err : r.err.substr(0, r.err.size() - 1);
  last = last.substr(last.rfind('\n') == std::string::npos ? 0 : last.rfind('\n') + 1);
  check(last.rfind("shadowref " + c.args.front(), 0) == 0, "the last line does not start with 'shadowref " + c.args.front() + "'");
  const std::string mention = expand(c.must_mention, dir);
  check(last.find(mention) != std::string::npos, "the last line does not name '" + mention + "'");
  for (const char* crash : {"terminate called", "Sanitizer", "runtime error", "Segmentation", "Aborted", "std::bad_alloc"})
    check(r.err.find(crash) == std::string::npos, std::string("stderr shows a crash: ") + crash);
  check(!fs::exists(dir / "out") && !fs::exists(dir / "file" / "out"), "the failed command left an output folder");
  fs::remove_all(dir);
  std::string report;
  for (const std::string& p : problems) report += "  - " + p + "\n";
  report += cmdline + "\nstderr:\n" + r.err;
  if (!c.known_bug.empty()) {
    if (problems.empty()) FAIL() << "XPASS: the known bug is fixed, drop known_bug from this case: " << c.known_bug;
    GTEST_SKIP() << "XFAIL (known bug, reported): " << c.known_bug << "\n" << report;
  }
  EXPECT_TRUE(problems.empty()) << report;
}

// Confinement: `shadowref conform --scenes FILE --out DIR` with a scene whose name climbs out of
// DIR ("../../escaped_scene" would put renders/<name>/ beside DIR and the reference cache's
// <name>-<key>/ above it) writes nothing outside DIR — the whole tree around DIR is unchanged — and
// nothing inside it either: it is refused before any work, as bad input.
std::vector<std::string> listing(const fs::path& root) {
  std::vector<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(root))
    out.push_back(fs::relative(e.path(), root).string() + (e.is_directory() ? "/" : " " + std::to_string(e.file_size())));
  std::sort(out.begin(), out.end());
  return out;
}

TEST(Confinement, ConformWithAnEscapingSceneNameWritesNothingOutsideOrInsideOut) {
  const fs::path root = fs::path(::testing::TempDir()) / "shadowref-confinement";
  fs::remove_all(root);
  const fs::path scene = root / "scenes" / "escape.json", out = root / "work" / "a" / "out";
  write_text(scene, good_scene("name", R"("../../escaped_scene")"));
  fs::create_directories(out.parent_path());
  const std::vector<std::string> before = listing(root);
  const CommandResult r = run_command({"/usr/bin/timeout", "120", SHADOWREF_EXE, "conform", "--scenes", scene.string(),
                                       "--out", out.string(), "--techniques", "planar", "--spp", "1", "--quiet"});
  EXPECT_EQ(r.exit_code, 4) << r.err;
  EXPECT_NE(r.err.find(scene.string() + ": name: must not contain '..'"), std::string::npos) << r.err;
  EXPECT_EQ(listing(root), before) << "conform wrote beside or inside --out";
  EXPECT_FALSE(fs::exists(out)) << "conform left an output folder";
  fs::remove_all(root);
}

// The one way to read a mesh outside the scene's folder is asked for by name, on the commands for
// local use (render, reference); without the flag the same scene is bad input.
TEST(Confinement, AllowMeshesOutsideIsTheOnlyWayToReadAMeshAboveTheSceneFolder) {
  const fs::path root = fs::path(::testing::TempDir()) / "shadowref-allow-outside";
  fs::remove_all(root);
  write_text(root / "outside.obj", "v 0 1 0\nv 1 1 0\nv 0 1 1\nf 1 3 2\n");
  write_text(root / "scenes" / "s.json", good_scene("objects", mesh_object("../outside.obj")));
  for (const std::string sub : {"render", "reference"}) {
    std::vector<std::string> args = {"/usr/bin/timeout", "120", SHADOWREF_EXE, sub, "--scene", (root / "scenes" / "s.json").string(),
                                     "--out", (root / ("out-" + sub)).string()};
    if (sub == "render") args.insert(args.end(), {"--technique", "planar"});
    else args.insert(args.end(), {"--spp", "1", "--quiet"});
    const CommandResult refused = run_command(args);
    EXPECT_EQ(refused.exit_code, 4) << sub << ": " << refused.err;
    EXPECT_NE(refused.err.find("objects[1].shape.file: '../outside.obj' resolves to"), std::string::npos) << refused.err;
    EXPECT_FALSE(fs::exists(root / ("out-" + sub)));
    args.push_back("--allow-meshes-outside");
    const CommandResult allowed = run_command(args);
    EXPECT_EQ(allowed.exit_code, 0) << sub << ": " << allowed.err;
    EXPECT_TRUE(fs::exists(root / ("out-" + sub) / "mask.png")) << sub;
  }
  fs::remove_all(root);
}

// ------------------------------------------------------------------ hostile candidate folders

// An engine team's candidate folder judged by `shadowref conform --candidate-dir`: one bad scene
// folder does not stop the others. The bad scene's case is an ERROR whose one line (in report.json
// and on the terminal) names the file and what is wrong, the run exits 2 (failures), the other
// scene is judged, report.json is valid JSON, and nothing outside --out changes.
struct CandidateCase {
  std::string name;
  std::string scene;                                    // "one" (one light) or "two" (two lights)
  std::function<void(const fs::path& scene_dir)> spoil;  // applied to a valid candidate folder
  std::string must_mention;                              // "@" is the scene's candidate folder
};

void PrintTo(const CandidateCase& c, std::ostream* os) { *os << c.name; }

std::vector<CandidateCase> candidate_cases() {
  const auto text = [](std::string file, std::string content) {
    return [file, content](const fs::path& d) { write_text(d / file, content); };
  };
  return {
      // A decompression bomb stops at the header: the size is checked before any pixel is decoded.
      {"absurd_header", "one", text("mask.png", png_header_only(1000000, 1000000)), "@/mask.png"},
      {"bomb_within_limit", "one", [](const fs::path& d) { write_png(d / "mask.png", 8192, 8192, 1, 0); },
       "@/mask.png: candidate is 8192x8192, reference is 32x32"},
      {"wrong_size", "one", [](const fs::path& d) { write_png(d / "mask.png", 16, 32, 1, 0); },
       "@/mask.png: candidate is 16x32, reference is 32x32"},
      {"off_values", "one", [](const fs::path& d) { write_png(d / "mask.png", 32, 32, 1, 10); },
       "@/mask.png: 1024 pixel(s) hold values other than 255"},
      {"truncated", "one",
       [](const fs::path& d) { fs::resize_file(d / "mask.png", fs::file_size(d / "mask.png") / 2); }, "@/mask.png"},
      {"folder_named_mask", "one",
       [](const fs::path& d) {
         fs::remove(d / "mask.png");
         fs::create_directories(d / "mask.png");
       },
       "@/mask.png: not a regular file"},
      {"dangling_link", "one",
       [](const fs::path& d) {
         fs::remove(d / "mask.png");
         fs::create_symlink("/nonexistent/mask.png", d / "mask.png");
       },
       "@/mask.png: no such file"},
      {"per_light_mask_for_one_light", "one",
       [](const fs::path& d) { fs::copy_file(d / "mask.png", d / "mask_0.png"); },
       "@/mask_0.png: the reference has 1 light(s)"},
      {"missing_light_mask", "two", [](const fs::path& d) { fs::remove(d / "mask_1.png"); }, "@/mask_1.png: no such file"},
      {"extra_light_mask", "two", [](const fs::path& d) { fs::copy_file(d / "mask_0.png", d / "mask_2.png"); },
       "@/mask_2.png: the reference has 2 light(s)"},
      {"single_mask_beside_per_light", "two", [](const fs::path& d) { fs::copy_file(d / "mask_0.png", d / "mask.png"); },
       "@/mask.png: the reference has 2 light(s)"},
      {"declaration_wrong_type", "one", text("candidate.json", R"({"shadow_map_size": "big"})"),
       "@/candidate.json: shadow_map_size: must be an integer"},
      {"declaration_malformed", "one", text("candidate.json", R"({"producer": )"), "@/candidate.json"},
      {"declaration_unknown_key", "one", text("candidate.json", R"({"shadowmapsize": 2048})"), "shadowmapsize"},
      {"declaration_out_of_range", "one", text("candidate.json", R"({"shadow_map_size": 100000000})"), "shadow_map_size"},
      {"declaration_not_utf8", "one", text("candidate.json", "{\"producer\": \"\xff\xfe\"}"), "@/candidate.json"},
      {"declaration_light_taps_out_of_range", "one", text("candidate.json", R"({"light_taps": 0})"),
       "@/candidate.json: light_taps: must be in [1, 64]"},
      {"declaration_sampling_unknown", "one", text("candidate.json", R"({"sampling": "poisson"})"),
       "@/candidate.json: sampling: must be \"grid\" or \"random\""},
      {"declaration_light_unknown_key", "two", text("candidate.json", R"({"lights": [{}, {"bias": 0.001}]})"),
       "@/candidate.json: lights[1].bias: unknown key"},
      {"declaration_light_not_per_light", "two", text("candidate.json", R"({"lights": [{"technique": "pcss"}]})"),
       "@/candidate.json: lights[0].technique: not a per-light key"},
      {"declaration_light_wrong_type", "two", text("candidate.json", R"({"lights": [{"slope_bias_texels": "2"}]})"),
       "@/candidate.json: lights[0].slope_bias_texels: must be a number"},
      {"declaration_distance_bias_without_range", "one", text("candidate.json", R"({"depth": "distance", "depth_bias": 0.01})"),
       "@/candidate.json: depth_range: a \"distance\" map's depth_bias is in units of its range"},
      {"declaration_atlas_tile_and_map_size", "one",
       text("candidate.json", R"({"shadow_map_size": 512, "atlas_tile": {"size": 683, "guard_band": 8}})"),
       "@/candidate.json: atlas_tile: give the tile or shadow_map_size, not both"},
      {"declaration_atlas_tile_all_guard_band", "two", text("candidate.json", R"({"lights": [{"atlas_tile": {"size": 64, "guard_band": 30}}]})"),
       "@/candidate.json: lights[0].atlas_tile: the size less twice the guard band must be in [16, 16384]"},
      {"declaration_atlas_tile_not_integers", "one", text("candidate.json", R"({"atlas_tile": {"size": "683"}})"),
       "@/candidate.json: atlas_tile: must be {\"size\": texels, \"guard_band\": texels per side} (integers)"},
      {"declaration_more_lights_than_scene", "one", text("candidate.json", R"({"lights": [{}, {}]})"),
       "@/candidate.json: lights: 2 entries, but scene 'one' has 1 light(s)"},
  };
}

void write_candidate_catalogue(const fs::path& dir) {
  write_text(dir / "cat" / "one.json", good_scene("name", R"("one")"));
  std::string two = good_scene("lights", R"([{"type": "point", "position": [2, 6, 1]}, {"type": "point", "position": [-2, 5, 0]}])");
  two.replace(two.find(R"("bad")"), 5, R"("two")");
  write_text(dir / "cat" / "two.json", two);
  write_png(dir / "cand" / "one" / "mask.png", 32, 32, 1, 255);
  write_png(dir / "cand" / "two" / "mask_0.png", 32, 32, 1, 255);
  write_png(dir / "cand" / "two" / "mask_1.png", 32, 32, 1, 255);
}

// Every entry under `root` except the subtree `skip`, with sizes.
std::vector<std::string> listing_without(const fs::path& root, const fs::path& skip) {
  std::vector<std::string> out;
  for (auto it = fs::recursive_directory_iterator(root); it != fs::recursive_directory_iterator(); ++it) {
    if (it->path() == skip) {
      it.disable_recursion_pending();
      continue;
    }
    std::error_code ec;
    out.push_back(fs::relative(it->path(), root).string() +
                  (it->is_symlink() ? " link" : it->is_directory() ? "/" : " " + std::to_string(it->file_size(ec))));
  }
  std::sort(out.begin(), out.end());
  return out;
}

class HostileCandidate : public ::testing::TestWithParam<CandidateCase> {};

TEST_P(HostileCandidate, TheSceneIsAnErrorNamingTheFileTheOthersAreJudged) {
  const CandidateCase& c = GetParam();
  const fs::path dir = fs::path(::testing::TempDir()) / ("shadowref-hostile-" + c.name);
  fs::remove_all(dir);
  write_candidate_catalogue(dir);
  const fs::path scene_dir = dir / "cand" / c.scene;
  c.spoil(scene_dir);
  const std::vector<std::string> before = listing_without(dir, dir / "out");
  const CommandResult r = run_command({"/usr/bin/timeout", "120", SHADOWREF_EXE, "conform", "--catalogue", (dir / "cat").string(),
                                       "--candidate-dir", (dir / "cand").string(), "--technique", "shadowmap", "--spp", "1",
                                       "--out", (dir / "out").string(), "--quiet"});
  ASSERT_NE(r.exit_code, 124) << "hung";
  EXPECT_EQ(r.exit_code, 2) << r.err << r.out;
  for (const char* crash : {"terminate called", "Sanitizer", "runtime error", "Segmentation", "Aborted", "internal error"})
    EXPECT_EQ((r.err + r.out).find(crash), std::string::npos) << crash << "\n" << r.err;
  std::string mention = c.must_mention;
  for (std::size_t at; (at = mention.find('@')) != std::string::npos;) mention.replace(at, 1, scene_dir.string());
  std::ifstream in(dir / "out" / "report.json");
  const nlohmann::json report = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  ASSERT_FALSE(report.is_discarded()) << "report.json is missing or not JSON";
  int errors = 0, judged = 0;
  for (const nlohmann::json& k : report.at("cases")) {
    if (k.at("scene") == c.scene) {
      EXPECT_EQ(k.at("status"), "ERROR");
      const std::string line = k.value("error", std::string());
      EXPECT_NE(line.find(mention), std::string::npos) << "the error does not name '" << mention << "': " << line;
      EXPECT_EQ(line.find('\n'), std::string::npos) << "more than one line: " << line;
      EXPECT_NE((r.err + r.out).find(line), std::string::npos) << "the terminal does not show: " << line;
      ++errors;
    } else {
      EXPECT_NE(k.at("status"), "ERROR") << k.at("scene") << ": " << k.value("error", std::string());
      ++judged;
    }
  }
  EXPECT_EQ(errors, 1);
  EXPECT_EQ(judged, 1);
  EXPECT_EQ(listing_without(dir, dir / "out"), before) << "conform changed something outside --out";
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Folders, HostileCandidate, ::testing::ValuesIn(candidate_cases()),
                         [](const ::testing::TestParamInfo<CandidateCase>& p) { return p.param.name; });

// A soft technique's candidate judged against an area light must bring its lit fraction: without
// visibility.png the case is an ERROR with one line naming the file, and nothing is written outside --out.
TEST(HostileCandidateSoft, ALitFractionMissingBesideTheMaskIsOneLine) {
  const fs::path dir = fs::temp_directory_path() / "shadowref-bad-input-soft";
  fs::remove_all(dir);
  std::string scene =
      good_scene("lights", R"([{"type": "rect", "corner": [-0.5, 6, -0.5], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1], "samples": 2}])");
  scene.replace(scene.find(R"("bad")"), 5, R"("soft")");
  write_text(dir / "cat" / "soft.json", scene);
  write_png(dir / "cand" / "soft" / "mask.png", 32, 32, 1, 255);
  const std::vector<std::string> before = listing_without(dir, dir / "out");
  const CommandResult r = run_command({"/usr/bin/timeout", "120", SHADOWREF_EXE, "conform", "--catalogue", (dir / "cat").string(),
                                       "--candidate-dir", (dir / "cand").string(), "--technique", "pcss", "--spp", "1",
                                       "--out", (dir / "out").string(), "--quiet"});
  EXPECT_EQ(r.exit_code, 2) << r.err << r.out;
  std::ifstream in(dir / "out" / "report.json");
  const nlohmann::json report = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  ASSERT_FALSE(report.is_discarded()) << "report.json is missing or not JSON";
  ASSERT_EQ(report.at("cases").size(), 1u);
  const nlohmann::json& k = report.at("cases")[0];
  EXPECT_EQ(k.at("status"), "ERROR");
  const std::string line = k.value("error", std::string());
  EXPECT_NE(line.find((dir / "cand" / "soft" / "visibility.png").string() + ": no such file"), std::string::npos) << line;
  EXPECT_EQ(line.find('\n'), std::string::npos) << line;
  EXPECT_EQ(listing_without(dir, dir / "out"), before) << "conform changed something outside --out";
  fs::remove_all(dir);
}

// A candidate folder whose name is not UTF-8 (legal on Linux): judged as any other, and report.json
// stays valid JSON (the name's invalid bytes become U+FFFD there).
TEST(HostileCandidateNames, ANonUtf8FolderNameIsJudgedAndReportedAsValidJson) {
  const fs::path dir = fs::path(::testing::TempDir()) / "shadowref-hostile-non-utf8";
  fs::remove_all(dir);
  write_candidate_catalogue(dir);
  const fs::path odd = dir / "cand\xff\xfe";
  fs::rename(dir / "cand", odd);
  write_text(odd / "one" / "notes\xff.txt", "a file the judge does not read\n");
  const CommandResult r = run_command({"/usr/bin/timeout", "120", SHADOWREF_EXE, "conform", "--catalogue", (dir / "cat").string(),
                                       "--candidate-dir", odd.string(), "--technique", "shadowmap", "--spp", "1", "--out",
                                       (dir / "out").string(), "--quiet"});
  EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 1 || r.exit_code == 2) << r.err;
  EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
  std::ifstream in(dir / "out" / "report.json");
  const nlohmann::json report = nlohmann::json::parse(in, nullptr, false);
  ASSERT_FALSE(report.is_discarded()) << "report.json is missing or not JSON\n" << r.err;
  for (const nlohmann::json& k : report.at("cases")) EXPECT_NE(k.at("status"), "ERROR") << k.dump();
  fs::remove_all(dir);
}

// A symlink forest (how CI systems lay out candidate folders): links are followed, and report.json
// names each input read through a link that leaves --candidate-dir, with its real location; a link
// that stays inside is not named; nothing is written through a link.
TEST(Confinement, InputsReadThroughLinksLeavingTheCandidateFolderAreNamed) {
  const fs::path dir = fs::path(::testing::TempDir()) / "shadowref-symlink-forest";
  fs::remove_all(dir);
  write_candidate_catalogue(dir);
  write_png(dir / "elsewhere" / "mask.png", 32, 32, 1, 255);
  fs::remove(dir / "cand" / "one" / "mask.png");
  fs::create_symlink(dir / "elsewhere" / "mask.png", dir / "cand" / "one" / "mask.png");
  fs::remove(dir / "cand" / "two" / "mask_1.png");
  fs::create_symlink("mask_0.png", dir / "cand" / "two" / "mask_1.png");  // stays inside
  const std::vector<std::string> before = listing_without(dir, dir / "out");
  const CommandResult r = run_command({"/usr/bin/timeout", "120", SHADOWREF_EXE, "conform", "--catalogue", (dir / "cat").string(),
                                       "--candidate-dir", (dir / "cand").string(), "--technique", "shadowmap", "--spp", "1",
                                       "--out", (dir / "out").string()});
  EXPECT_TRUE(r.exit_code >= 0 && r.exit_code <= 2) << r.err;
  EXPECT_NE(r.out.find("note: 1 candidate file(s) were read through symbolic links"), std::string::npos) << r.out;
  std::ifstream in(dir / "out" / "report.json");
  const nlohmann::json report = nlohmann::json::parse(in, nullptr, false);
  ASSERT_FALSE(report.is_discarded());
  EXPECT_EQ(report.value("inputs_read_through_links", -1), 1);
  for (const nlohmann::json& k : report.at("cases")) {
    if (k.at("scene") == "one") {
      ASSERT_TRUE(k.contains("read_through_links")) << k.dump();
      ASSERT_EQ(k["read_through_links"].size(), 1u);
      EXPECT_EQ(k["read_through_links"][0]["file"], (dir / "cand" / "one" / "mask.png").string());
      EXPECT_EQ(k["read_through_links"][0]["resolves_to"], (dir / "elsewhere" / "mask.png").string());
    } else {
      EXPECT_FALSE(k.contains("read_through_links")) << k.dump();
    }
  }
  EXPECT_EQ(listing_without(dir, dir / "out"), before) << "conform changed something outside --out";
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Table, BadInput, ::testing::ValuesIn(make_cases()),
                         [](const ::testing::TestParamInfo<Case>& param_info) {
                           std::string n = param_info.param.name;
                           std::replace(n.begin(), n.end(), '-', '_');
                           return n;
                         });

}  // namespace
}  // namespace shadowref::test
