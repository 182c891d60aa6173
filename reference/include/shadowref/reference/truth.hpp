// shadowref/reference/truth.hpp — what of a reference mask is its truth, and whether two agree.
//
// A decided pixel (decided = 255) is one where every sub-sample and nudged shadow ray of the
// reference gave the same answer: its mask value is the truth, the same on every machine. An
// undecided pixel's mask value is the reference's best guess, and that guess rests on hit
// distances and barycentrics within a few ulps of a boundary, which differ between Embree's
// kernels (SSE, AVX2 and AVX-512 traverse and intersect with their own arithmetic): two machines
// may guess differently. The judge never reads an undecided pixel's value, so verdicts agree.
//
// Two references of one scene and light agree when their decided images are identical and their
// masks are identical on every decided pixel; the undecided pixels whose guesses differ are
// counted as information only.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

namespace shadowref::reference {

struct TruthComparison {
  std::size_t decided_differ = 0;  // pixels decided in one reference and undecided in the other
  std::size_t truth_differ = 0;    // pixels decided in both whose mask values differ
  std::size_t guesses_differ = 0;  // pixels undecided in either whose mask values differ: information
  // The first pixel (row-major) counted in decided_differ or truth_differ; -1 when they are 0.
  std::ptrdiff_t first = -1;

  bool agree() const { return decided_differ == 0 && truth_differ == 0; }
};

// Compares two references' masks and decided images of one light, pixel by pixel. The four spans
// have the same length (throws std::invalid_argument otherwise). Cost: one pass over the pixels.
TruthComparison compare_truth(std::span<const std::uint8_t> mask_a, std::span<const std::uint8_t> decided_a,
                              std::span<const std::uint8_t> mask_b, std::span<const std::uint8_t> decided_b);

}  // namespace shadowref::reference
