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
//   {{scenes}}               one table row per manifest scene: "| name | WxH | lights | description |"
// Table rows are joined by newlines, the last without one (the template ends the line). A leading
// HTML comment (<!-- ... -->, the template's own notes) and the newline after it are dropped.
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

namespace shadowref::pack {

// The template's path under the data folder (conform::data_dir(): the source tree from a build
// tree, <prefix>/share/shadowref when installed).
std::filesystem::path readme_template_path(const std::filesystem::path& data_dir);

// The template at `file`. Throws std::runtime_error naming the file when it cannot be read (an
// installation without its data: not the user's input).
std::string read_readme_template(const std::filesystem::path& file);

// `templ` filled: `manifest` is the pack's manifest.json (its "scenes": name, resolution, lights,
// description). Throws std::invalid_argument naming the placeholder for an unknown one, an unknown
// name in one, or an unclosed "{{". Cost: one pass over the text.
std::string fill_readme(const std::string& templ, const nlohmann::json& manifest);

}  // namespace shadowref::pack
