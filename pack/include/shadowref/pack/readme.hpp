// shadowref/pack/readme.hpp — the pack's README.md: a template (pack/README.template.md, installed
// as <data>/pack/README.template.md) filled from the contract's tables, so that no README prose lives
// in C++ and no table is copied into prose.
//
// Placeholders, {{...}} in the template:
//   {{technique_names}}      every technique name of outputs::kTechniques, comma-separated, in order
//   {{technique:NAME}}       `NAME`; refused unless NAME is in kTechniques (a renamed technique
//                            breaks the fill, not the README)
//   {{error_image_colours}}  one Markdown table row per outputs::kErrorClasses row: "| rgb(..) colour | legend |"
//   {{colour_name:NAME}}     the colour name of kErrorClasses' row called NAME
//   {{json_key:NAME}}        the report.json count of that row
//   {{scenes}}               one table row per manifest scene: "| name | WxH | lights | units | description |",
//                            the description followed by a bold warning for each light whose point sits
//                            nearer to a surface than kCloseLightShare of the scene's size
// Table rows are joined by newlines, the last without one (the template ends the line). A leading
// HTML comment (<!-- ... -->, the template's own notes) and the newline after it are dropped.
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

namespace shadowref::pack {

// A light this near to a surface, as a share of the scene's size (its bounds' diagonal), is said in
// the scenes table: an engine's shadow camera then needs a near plane below that distance (three.js's
// point-light default is 0.5 units, half a millimetre in a scene of millimetres), and the surface is
// lit at grazing angles around the light. Two catalogue scenes are said (the pack's manifest.json):
// the Cornell box's light, 0.1 mm (0.01 %) under its ceiling, and light_near_caster's, 0.35 m (0.8 %)
// over its plate, within three.js's default near plane; the next, level_cut's lantern, is at 3.4 %.
inline constexpr double kCloseLightShare = 0.01;

// The template's path under the data folder (conform::data_dir(): the source tree from a build
// tree, <prefix>/share/shadowref when installed).
std::filesystem::path readme_template_path(const std::filesystem::path& data_dir);

// The template at `file`. Throws std::runtime_error naming the file when it cannot be read (an
// installation without its data: not the user's input).
std::string read_readme_template(const std::filesystem::path& file);

// `templ` filled: `manifest` is the pack's manifest.json (its "scenes": name, resolution, lights,
// units, size, light_clearance, description). Throws std::invalid_argument naming the placeholder for an unknown one, an unknown
// name in one, or an unclosed "{{". Cost: one pass over the text.
std::string fill_readme(const std::string& templ, const nlohmann::json& manifest);

}  // namespace shadowref::pack
