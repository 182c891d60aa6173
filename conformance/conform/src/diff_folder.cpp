// diff_folder.cpp — `shadowref diff --out DIR`: the page and its images (diff_folder.hpp).
#include "shadowref/conform/diff_folder.hpp"

#include <algorithm>
#include <cctype>
#include <string>

#include <nlohmann/json.hpp>

#include "shadowref/conform/mask_difference.hpp"
#include "shadowref/outputs/atomic_file.hpp"
#include "shadowref/outputs/errors.hpp"
#include "shadowref/outputs/image_io.hpp"
#include "shadowref/outputs/staged_folder.hpp"
#include "shadowref/report/diff_html.hpp"

namespace shadowref::conform {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr const char* kImages = "diff-images";

// `name` with only letters, digits, '-', '_' and '.' kept (never "." or ".." alone): a report.json's
// scene and mask names become file names under DIR, and must not lead out of it.
std::string file_name_part(const std::string& name) {
  std::string out;
  for (char c : name) out += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.' ? c : '_';
  return out.empty() || out == "." || out == ".." ? "_" + out : out;
}

// Copies one run's image into the staged folder; the page's relative path, "" when the run has none.
std::string copy_image(const fs::path& from, const outputs::StagedFolder& staged, const std::string& rel) {
  if (from.empty()) return "";
  outputs::copy_file_atomically(from, staged.path() / rel);
  return std::string(kImages) + "/" + rel;
}

// One light's images of a changed case: both runs' copies and, for masks of one size, the picture
// of where they differ.
json light_images(const CaseDiff& c, std::size_t i, const outputs::StagedFolder& staged, const std::string& folder) {
  const DiffLight* a = c.a && i < c.a->lights.size() ? &c.a->lights[i] : nullptr;
  const DiffLight* b = c.b && i < c.b->lights.size() ? &c.b->lights[i] : nullptr;
  const std::string mask = a ? a->mask : b->mask, part = file_name_part(mask);
  json l = {{"mask", mask}, {"a_candidate", ""}, {"a_error", ""}, {"b_candidate", ""}, {"b_error", ""}, {"difference", ""}};
  if (a) {
    l["a_candidate"] = copy_image(a->candidate, staged, folder + "a_candidate_" + part);
    l["a_error"] = copy_image(a->error, staged, folder + "a_error_" + part);
  }
  if (b) {
    l["b_candidate"] = copy_image(b->candidate, staged, folder + "b_candidate_" + part);
    l["b_error"] = copy_image(b->error, staged, folder + "b_error_" + part);
  }
  // The masks' comparison says when they are comparable; only then is there a picture.
  if (a && b && c.masks.not_compared.empty() && i < c.masks.differ.size()) {
    const outputs::Image8 ia = outputs::read_image8(a->candidate, 1), ib = outputs::read_image8(b->candidate, 1);
    outputs::write_png(paint_mask_difference(ia, ib), staged.path() / (folder + "difference_" + part));
    l["difference"] = std::string(kImages) + "/" + folder + "difference_" + part;
    l["differ"] = c.masks.differ[i];
  }
  return l;
}

json legend_json() {
  json legend = json::array();
  for (const MaskDifferenceClass& m : kMaskDifferenceClasses)
    legend.push_back({{"name", m.name}, {"colour", {m.colour[0], m.colour[1], m.colour[2]}}, {"legend", m.legend}});
  return legend;
}

}  // namespace

fs::path write_diff_folder(const RunDiff& diff, const fs::path& out) {
  json page = to_json(diff);
  page["legend"] = legend_json();
  outputs::StagedFolder staged(out / kImages);
  std::size_t row = 0;
  for (const CaseDiff& c : diff.cases) {
    if (!c.changed()) continue;
    const std::string folder =
        std::to_string(row + 1) + "-" + file_name_part(c.scene) + "-" + file_name_part(c.technique) + "/";
    std::error_code ec;
    fs::create_directories(staged.path() / folder, ec);
    if (ec) throw outputs::FileError(staged.final_path() / folder, "create the folder", ec.value());
    const std::size_t lights = std::max(c.a ? c.a->lights.size() : 0, c.b ? c.b->lights.size() : 0);
    json images = json::array();
    for (std::size_t i = 0; i < lights; ++i) images.push_back(light_images(c, i, staged, folder));
    page["cases"][row]["images"] = images;
    ++row;
  }
  staged.commit();
  const fs::path html = out / "diff.html";
  outputs::write_file_atomically(html, report::render_diff_html(page));
  return html;
}

}  // namespace shadowref::conform
