// mask_compare_fuzzer.cpp — libFuzzer target: the mask comparison (compare::compare_folders, as
// `shadowref compare` calls it) on three arbitrary files: the reference's mask.png and
// decided.png and the candidate's mask.png, so image headers, sizes, channel counts, pixel formats
// and truncation are all the fuzzer's to choose. Input layout: two little-endian 16-bit lengths,
// then the reference mask bytes, the decided bytes, and the rest is the candidate mask. Refusals
// must be CompareError (BadInput or SizeMismatch).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <filesystem>

#include "fuzz_files.hpp"
#include "shadowref/compare/compare.hpp"
#include "shadowref/compare/thresholds.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace fs = std::filesystem;
  if (size < 4) return 0;
  const std::size_t a = std::min<std::size_t>(data[0] | (data[1] << 8), size - 4);
  const std::size_t b = std::min<std::size_t>(data[2] | (data[3] << 8), size - 4 - a);
  static const fs::path ref = shadowref::fuzz::scratch_dir() / "reference";
  static const fs::path cand = shadowref::fuzz::scratch_dir() / "candidate";
  fs::create_directories(ref);
  fs::create_directories(cand);
  shadowref::fuzz::write_file(ref / "mask.png", data + 4, a);
  shadowref::fuzz::write_file(ref / "decided.png", data + 4 + a, b);
  shadowref::fuzz::write_file(cand / "mask.png", data + 4 + a + b, size - 4 - a - b);
  try {
    (void)shadowref::compare::compare_folders(ref, cand, shadowref::compare::threshold_for("shadowmap"));
  } catch (const shadowref::compare::CompareError&) {
  }
  return 0;
}
