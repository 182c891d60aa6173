// shadowref/conform/resolving_power.hpp — what a verdict could have seen: the known blatant errors
// applied to the reference's own masks, each judged under the candidate's declaration by the same
// comparison as the candidate.
//
// A PASS says the candidate's errors were within what its declaration explains; it does not say how
// large an error that declaration would have let through. A 512-texel map of the candidate's own
// views, or a camera at the light, can explain a one-pixel shift of every shadow. So every judged
// case is asked, with the same threshold, causes and declaration, about probes of the reference's own
// masks (the probes follow the declaration grid's blatant mutants, conformance/tests/):
//   shifted 1 and 2 px in the eight directions (shadows move, surfaces stay),
//   the shadows grown and shrunk by 1 px,
//   an 8 × 8 tile swapped with the one to its right where that changes most pixels.
// A probe that changes decided pixels and does not FAIL is one the case is blind to. Soft techniques are probed on their masks
// alone (a probe of the lit fraction would need a fraction to move; the mask's is what it shows).
//
// A probe that changes no decided pixel (a shift along a straight boundary) proves nothing: it counts
// for neither side.
//
// Cost: 19 mask comparisons per light, each asking the cause model about the probe's wrong pixels
// (a few thousand at 256²), first without the displaced-shadow search; the judge caches the answer
// per reference, declaration and threshold. The default catalogue's judging: 2.6 s -> 7.2 s
// (docs/tolerance-model.md).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "shadowref/compare/compare.hpp"

namespace shadowref::conform {

// The kinds of blatant error probed, each a group of probes.
enum class ProbeKind { Shift1, Shift2, Grown1, Shrunk1, Tile8 };
const char* to_string(ProbeKind k);  // "1-px shifts", "2-px shifts", "1-px growth", "1-px shrinkage", "8x8 tiles"

struct Probe {
  ProbeKind kind;
  std::string name;  // "shifted 1 px right and down", "grown 1 px", ...
  compare::Verdict verdict = compare::Verdict::Pass;
  std::size_t wrong = 0, unexplained = 0;  // on the decided pixels, summed over the lights
};

struct ResolvingPower {
  std::vector<Probe> probes;
  // A probe that changes no decided pixel (a shift along a straight boundary, any probe where no
  // cast shadow is in view) shows nothing and counts for neither side. Per kind: `resolved`, every
  // probe that changes a decided pixel FAILs; `blind`, one of them does not; `unseen`, none changes one.
  std::vector<ProbeKind> resolved, blind, unseen;
  // "resolves 1-px shifts, 2-px shifts, 1-px growth, 1-px shrinkage and 8x8 tiles", or "blind to
  // 1-px shifts (3 of 7 pass) under this declaration; resolves ...; no 8x8 tile changes a decided pixel".
  std::string summary() const;
  bool blind_to(ProbeKind k) const;
  bool sees_nothing_of(ProbeKind k) const;  // k is in `unseen`
};

// The probes of the reference folder's masks (mask.png or mask_<i>.png, decided.png or
// decided_<i>.png, `lights` of them) judged by `threshold` with `options` (its lit-fraction bounds
// ignored). Throws outputs::InputError when a reference file cannot be read.
ResolvingPower resolving_power(const std::filesystem::path& reference_dir, std::size_t lights,
                               const compare::Threshold& threshold, const compare::CompareOptions& options);

// A case's resolving power as report.json and `shadowref compare --json` give it: {"summary",
// "blind_to": [kinds], "unseen": [kinds], "probes": [{"probe", "verdict", "wrong", "unexplained"}]}.
nlohmann::json resolving_power_json(const ResolvingPower& r);

}  // namespace shadowref::conform
