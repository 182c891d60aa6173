// candidate_fuzzer.cpp — libFuzzer target: a candidate folder as an engine team hands it to
// `shadowref conform --candidate-dir`, judged against a fixed two-light reference (8 × 8 masks and
// decided images, written once): its candidate.json (outputs::read_declaration) and its per-light
// masks (compare::compare_folders, which finds and checks the mask set). The fuzzer chooses the
// declaration's text, both masks' bytes and which mask files exist (a missing per-light mask, an
// extra mask_2.png, a one-light mask.png beside the per-light ones).
// Input layout: one flag byte (bit 0: mask_0.png, bit 1: mask_1.png, bit 2: mask.png, bit 3:
// mask_2.png), two little-endian 16-bit lengths (candidate.json, mask_0), then candidate.json,
// mask_0's bytes, and the rest is mask_1 (mask.png and mask_2.png copy mask_0's bytes).
// Refusals must be outputs::InputError (BadInput or SizeMismatch): what conform reports as the
// case's ERROR naming the file; anything else escaping is a finding.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <filesystem>

#include "fuzz_files.hpp"
#include "shadowref/compare/compare.hpp"
#include "shadowref/compare/thresholds.hpp"
#include "shadowref/outputs/candidate.hpp"
#include "shadowref/outputs/errors.hpp"
#include "shadowref/outputs/image.hpp"
#include "shadowref/outputs/image_io.hpp"

namespace {

namespace fs = std::filesystem;
using namespace shadowref;

outputs::Image8 filled(std::uint8_t value) {
  outputs::Image8 image;
  image.width = image.height = 8;
  image.pixels.assign(64, value);
  return image;
}

const fs::path& reference_folder() {
  static const fs::path dir = [] {
    const fs::path d = fuzz::scratch_dir() / "reference";
    fs::create_directories(d);
    outputs::Image8 lit = filled(outputs::kMaskLit), shadowed = filled(outputs::kMaskShadowed);
    for (int i = 0; i < 16; ++i) lit.pixels[static_cast<std::size_t>(i)] = outputs::kMaskNoSurface;
    outputs::write_png(lit, d / "mask_0.png");
    outputs::write_png(shadowed, d / "mask_1.png");
    outputs::write_png(filled(255), d / "decided_0.png");
    outputs::write_png(filled(255), d / "decided_1.png");
    return d;
  }();
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 5) return 0;
  const unsigned flags = data[0];
  const std::size_t a = std::min<std::size_t>(data[1] | (data[2] << 8), size - 5);
  const std::size_t b = std::min<std::size_t>(data[3] | (data[4] << 8), size - 5 - a);
  const std::uint8_t* json = data + 5;
  const std::uint8_t* mask0 = json + a;
  const std::uint8_t* mask1 = mask0 + b;
  const std::size_t c = size - 5 - a - b;

  const fs::path& ref = reference_folder();
  static const fs::path cand = fuzz::scratch_dir() / "candidate";
  fs::remove_all(cand);
  fs::create_directories(cand);
  if (a > 0) fuzz::write_file(cand / outputs::kCandidateFile, json, a);
  if (flags & 1) fuzz::write_file(cand / "mask_0.png", mask0, b);
  if (flags & 2) fuzz::write_file(cand / "mask_1.png", mask1, c);
  if (flags & 4) fuzz::write_file(cand / "mask.png", mask0, b);
  if (flags & 8) fuzz::write_file(cand / "mask_2.png", mask0, b);
  try {
    const outputs::CandidateDeclaration d = outputs::read_declaration(cand, "shadowmap");
    (void)compare::compare_folders(ref, cand, compare::threshold_for(d.technique.empty() ? "shadowmap" : d.technique));
  } catch (const outputs::InputError&) {
  }
  return 0;
}
