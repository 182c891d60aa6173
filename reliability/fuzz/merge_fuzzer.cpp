// merge_fuzzer.cpp — libFuzzer target: the shards of a split run as `shadowref merge` reads them
// (conform::merge_shards), two shard folders whose report.json texts the fuzzer chooses: truncated,
// doubled, renamed, with paths that leave the report, numbers out of range, wrong types.
// Input layout: a little-endian 16-bit length, shard 1's report.json of that many bytes, then shard
// 2's. The seed corpus holds real shards of a two-scene run split in two.
// Refusals must be MergeRefused, std::invalid_argument (a report.json that does not parse) or
// outputs::InputError / FileError (a file a shard names that cannot be read): what `merge` reports
// with exit 4; anything else escaping (a JSON type error), a crash, a leak or a write outside the
// merge's --out is a finding.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "fuzz_files.hpp"
#include "shadowref/conform/merge.hpp"
#include "shadowref/outputs/errors.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace shadowref;
  namespace fs = std::filesystem;
  if (size < 2) return 0;
  const std::size_t first = std::min<std::size_t>(data[0] | (data[1] << 8), size - 2);
  static const fs::path root = fuzz::scratch_dir() / "merge";
  const fs::path a = root / "shard-1", b = root / "shard-2", out = root / "out";
  fs::remove_all(root);
  fs::create_directories(a);
  fs::create_directories(b);
  fuzz::write_file(a / "report.json", data + 2, first);
  fuzz::write_file(b / "report.json", data + 2 + first, size - 2 - first);
  conform::MergeOptions o;
  o.shards = {a, b};
  o.out = out;
  o.command_line = "shadowref merge";
  try {
    (void)conform::merge_shards(o);
  } catch (const conform::MergeRefused&) {
  } catch (const std::invalid_argument&) {
  } catch (const outputs::InputError&) {
  } catch (const outputs::FileError&) {
  }
  // Nothing may be written beside the shards and --out (a case named ../../escape, an image path
  // leaving the report).
  for (const auto& e : fs::directory_iterator(root))
    if (e.path() != a && e.path() != b && e.path() != out) __builtin_trap();
  return 0;
}
