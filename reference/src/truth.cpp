// truth.cpp — compare_truth: two references' masks agree on their decided pixels.
#include "shadowref/reference/truth.hpp"

#include <stdexcept>

namespace shadowref::reference {

TruthComparison compare_truth(std::span<const std::uint8_t> mask_a, std::span<const std::uint8_t> decided_a,
                              std::span<const std::uint8_t> mask_b, std::span<const std::uint8_t> decided_b) {
  const std::size_t n = mask_a.size();
  if (decided_a.size() != n || mask_b.size() != n || decided_b.size() != n)
    throw std::invalid_argument("compare_truth: the masks and decided images differ in size");
  TruthComparison out;
  for (std::size_t i = 0; i < n; ++i) {
    if (decided_a[i] != decided_b[i]) {
      ++out.decided_differ;
    } else if (mask_a[i] == mask_b[i]) {
      continue;
    } else if (decided_a[i] != 0) {
      ++out.truth_differ;
    } else {
      ++out.guesses_differ;  // an undecided pixel's guess: not part of the truth
      continue;
    }
    if (out.first < 0) out.first = static_cast<std::ptrdiff_t>(i);
  }
  return out;
}

}  // namespace shadowref::reference
