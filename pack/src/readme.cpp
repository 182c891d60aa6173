// readme.cpp — the pack's README from its template (readme.hpp).
#include "shadowref/pack/readme.hpp"

#include <cstdio>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string_view>

#include "shadowref/outputs/cause.hpp"
#include "shadowref/outputs/techniques.hpp"

namespace shadowref::pack {
namespace {

using nlohmann::json;

std::string technique_names() {
  std::string t;
  for (const outputs::TechniqueName& n : outputs::kTechniques) t += (t.empty() ? "" : ", ") + std::string(n.name);
  return t;
}

std::string error_image_colours() {
  std::string t;
  for (const outputs::ErrorClassRow& r : outputs::kErrorClasses)
    t += (t.empty() ? "" : "\n") + ("| " + outputs::rgb_text(r.colour) + " " + std::string(r.colour_name) + " | " +
                                    std::string(r.legend) + " |");
  return t;
}

// A number for prose: 3 significant digits, no exponent for the sizes scenes have.
std::string short_number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", v);
  return text;
}

// The warnings of a scene's row: each light whose point lies nearer to a surface than
// kCloseLightShare of the scene's size.
std::string light_warnings(const json& s) {
  std::string t;
  const json& clearance = s["light_clearance"];
  const double size = s["size"].get<double>();
  const std::string unit = s["units"]["symbol"].get<std::string>();
  for (std::size_t i = 0; i < clearance.size(); ++i) {
    if (clearance[i].is_null()) continue;
    const double d = clearance[i]["distance"].get<double>();
    if (!(d < kCloseLightShare * size)) continue;
    t += " **Light " + std::to_string(i) + " sits " + short_number(d) + " " + unit + " from a surface (" +
         clearance[i]["object"].get<std::string>() + ")**: a shadow camera's near plane beyond that clips it.";
  }
  return t.empty() ? t : "." + t;  // the descriptions end without a full stop
}

std::string scene_rows(const json& manifest) {
  std::string t;
  for (const json& s : manifest["scenes"])
    t += (t.empty() ? "" : "\n") + ("| " + s["name"].get<std::string>() + " | " + std::to_string(s["resolution"][0].get<int>()) +
                                    "x" + std::to_string(s["resolution"][1].get<int>()) + " | " +
                                    std::to_string(s["lights"].get<int>()) + " | " + s["units"]["name"].get<std::string>() +
                                    " | " + s["description"].get<std::string>() + light_warnings(s) + " |");
  return t;
}

// The text of placeholder `key` ("name" or "name:argument").
std::string placeholder(std::string_view key, const json& manifest) {
  const std::size_t colon = key.find(':');
  const std::string_view name = key.substr(0, colon);
  const std::string_view arg = colon == std::string_view::npos ? std::string_view() : key.substr(colon + 1);
  const auto refuse = [&key](const char* why) {
    return std::invalid_argument("README template: {{" + std::string(key) + "}}: " + why);
  };
  if (colon == std::string_view::npos) {
    if (name == "technique_names") return technique_names();
    if (name == "error_image_colours") return error_image_colours();
    if (name == "scenes") return scene_rows(manifest);
    throw refuse("no such placeholder");
  }
  if (name == "technique") {
    if (!outputs::find_technique_name(arg)) throw refuse("not a technique (outputs/techniques.hpp)");
    return "`" + std::string(arg) + "`";
  }
  if (name == "colour_name" || name == "json_key") {
    const outputs::ErrorClassRow* r = outputs::find_error_class(arg);
    if (!r) throw refuse("not an error class (outputs/cause.hpp)");
    if (name == "json_key" && r->json_key.empty()) throw refuse("this class has no report.json count");
    return std::string(name == "json_key" ? r->json_key : r->colour_name);
  }
  throw refuse("no such placeholder");
}

}  // namespace

std::filesystem::path readme_template_path(const std::filesystem::path& data_dir) {
  return data_dir / "pack" / "README.template.md";
}

std::string read_readme_template(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error(file.string() + ": cannot open the pack's README template (an installation without its data)");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw std::runtime_error(file.string() + ": cannot read the pack's README template");
  return text;
}

std::string fill_readme(const std::string& templ, const json& manifest) {
  std::string_view in = templ;
  if (in.starts_with("<!--")) {
    const std::size_t end = in.find("-->\n");
    if (end == std::string_view::npos) throw std::invalid_argument("README template: an unclosed leading comment");
    in.remove_prefix(end + 4);
  }
  std::string out;
  out.reserve(in.size() + 4096);
  for (std::size_t at = 0;;) {
    const std::size_t open = in.find("{{", at);
    if (open == std::string_view::npos) {
      out.append(in.substr(at));
      return out;
    }
    const std::size_t close = in.find("}}", open + 2);
    if (close == std::string_view::npos) throw std::invalid_argument("README template: an unclosed {{");
    out.append(in.substr(at, open - at));
    out += placeholder(in.substr(open + 2, close - open - 2), manifest);
    at = close + 2;
  }
}

}  // namespace shadowref::pack
