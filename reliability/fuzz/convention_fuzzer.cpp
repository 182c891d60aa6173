// convention_fuzzer.cpp — libFuzzer target: the command-line values that choose a run's
// conventions and sizes (`--convention NAME`, `--resolution WxH`, cli::parse_convention and
// cli::parse_size, as conform, render, reference and export call them) and what the chosen
// convention builds from numbers: the camera's view (view_from_scene) and projections
// (perspective_for, finite and infinite, and ortho_for).
// Input: text lines — convention name, resolution, then up to 16 numbers (parsed with the
// command line's parse_number: fovy, aspect, near, far, epsilon, eye xyz, target xyz, up xyz,
// and the box for ortho). Refusals must be BadInput (the command line's exit 4) or a mathlib
// error result; a matrix returned as valid must be finite (a silent NaN is a finding: abort).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "command.hpp"
#include "numbers.hpp"
#include "shadowref/convention.hpp"

namespace {

using namespace shadowref;

template <class M>
void require_finite(const M& m) {
  if (!m.allFinite()) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> lines(1);
  for (std::size_t i = 0; i < size; ++i) {
    if (data[i] == '\n') {
      if (lines.size() == 20) break;
      lines.emplace_back();
    } else {
      lines.back().push_back(static_cast<char>(data[i]));
    }
  }
  lines.resize(20);
  try {
    const RunConvention& c = cli::parse_convention(lines[0]);
    if (!lines[1].empty()) {
      const cli::Size2 s = cli::parse_size("--resolution", lines[1], 16384);
      if (s.width < 1 || s.height < 1 || s.width > 16384 || s.height > 16384) std::abort();
    }
    std::vector<double> v;
    for (std::size_t i = 2; i < lines.size() && !lines[i].empty(); ++i) v.push_back(cli::parse_number("value", lines[i]));
    v.resize(16, 1.0);
    if (const auto p = perspective_for<double>(c, v[0], v[1], v[2], v[3]); p) require_finite(*p);
    if (const auto p = perspective_for<double>(c, v[0], v[1], v[2], std::nullopt, v[4]); p) require_finite(*p);
    if (const auto p = perspective_for<float>(c, float(v[0]), float(v[1]), float(v[2]), float(v[3])); p) require_finite(*p);
    if (const auto o = ortho_for<double>(c, -v[5], v[5], -v[6], v[6], v[2], v[3]); o) require_finite(*o);
    const Vec3<double> eye(v[5], v[6], v[7]), target(v[8], v[9], v[10]), up(v[11], v[12], v[13]);
    if (const auto view = view_from_scene<double>(c, eye, target, up); view) require_finite(*view);
  } catch (const cli::BadInput&) {
  }
  return 0;
}
