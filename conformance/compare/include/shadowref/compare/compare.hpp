// shadowref/compare/compare.hpp — a candidate mask against the reference, on decided pixels only
// (docs/tolerance-model.md), in the spirit of the VK-GL-CTS rasterization verifier: a pixel the
// reference marks undecided (its sub-pixel samples disagree, or a nudge of the shadow ray flips
// it) may honestly go either way and is never counted; every decided pixel must match.
//
// Pixel classes (mask values, outputs/image.hpp): 255 lit, 0 shadowed, 128 no surface. A
// candidate holding any other value is refused (CompareError(BadInput) naming the file, the count
// and the first such pixel): the contract rounds nothing.
//
// Wrong kinds on a decided pixel:
//   false shadow  reference lit, candidate shadowed
//   false light   reference shadowed, candidate lit
//   coverage      surface in one, no surface in the other (the candidate's camera or geometry
//                 differs, which no shadow technique explains)
// (their colours, and the causes', in outputs::kErrorClasses).
// `largest_region` is the largest 8-connected set of wrong pixels: resolution error is thin and
// scattered along shadow boundaries, a real bug is a blob (thresholds.hpp caps it).
//
// Speed: one pass over the rows (vectorised: classes, edges, counts, the error image's colours),
// then the wrong pixels alone, from a list (kind, cause, cores, regions): what no wrong pixel
// needs is never done. Cost on a 2048² pair with a few thousand wrong pixels: about 7 ms on one
// core (bench/README.md), against OpenImageIO compare's 48.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "shadowref/outputs/cause.hpp"
#include "shadowref/outputs/errors.hpp"
#include "shadowref/outputs/image_io.hpp"
#include "shadowref/compare/displacement.hpp"
#include "shadowref/compare/thresholds.hpp"
#include "shadowref/compare/visibility.hpp"

namespace shadowref::compare {

// The contract's image type and input errors (outputs/), under the names the comparison uses.
using outputs::Image8;
using outputs::read_image8;
using CompareError = outputs::InputError;

struct MaskMetrics {
  int width = 0;
  int height = 0;
  std::size_t pixels = 0;           // width · height (summed over lights when accumulated)
  std::size_t decided = 0;          // pixels the reference marks decided
  std::size_t decided_surface = 0;  // decided pixels with a surface in the reference: the denominator
  std::size_t wrong = 0;            // false_shadow + false_light + coverage
  std::size_t false_shadow = 0;
  std::size_t false_light = 0;
  std::size_t coverage = 0;
  std::size_t off_values = 0;       // candidate values other than 0, 128, 255: always 0 (refused first, compare_mask)
  std::size_t regions = 0;          // 8-connected regions of wrong pixels
  std::size_t largest_region = 0;   // pixels in the largest one
  // The tolerance model (docs/tolerance-model.md): wrong pixels by cause, and the scale they are
  // judged against.
  std::size_t explained_texel = 0;  // wrong, within the declared map's texel footprint of a true boundary
  std::size_t explained_bias = 0;   // wrong, within the declared bias of a contact or a grazing surface
  std::size_t unexplained = 0;      // wrong and explained by nothing
  std::size_t unexplained_false_light = 0;  // of those, false light (the rest: false shadow or coverage)
  std::size_t unexplained_acne = 0;  // of those, self-shadowing: the receiver's own surface stored with too little bias
  std::size_t unexplained_zigzag = 0;  // of those, pixels no texel grid gives together (CompareOptions::impossible)
  std::size_t unexplained_core = 0; // unexplained pixels whose (2 kCoreRadius + 1)² neighbourhood is all unexplained
  std::size_t unexplained_false_light_core = 0;  // the same over the unexplained false light alone
  std::size_t edge_pixels = 0;      // reference pixels with a 4-neighbour of another class (lit,
                                    // shadowed, no surface): the length of every boundary, in pixels
  std::size_t invariant_pixels = 0; // undecided pixels judged because the scene's invariant holds there
  std::size_t displaced = 0;        // unexplained pixels right once the mask's shadows are moved back (displacement.hpp)
  // The most unexplained pixels in one (2 kClusterRadius + 1)² window centred on one of them: where
  // they lie, not how many (a local glitch is many in one place; resolution error is spread along edges).
  std::size_t densest_unexplained = 0;

  // wrong / decided_surface (0 when nothing is decided).
  double wrong_fraction() const;
  // unexplained / edge_pixels and (explained_texel + explained_bias) / edge_pixels: the numbers
  // thresholds judge (a ratio of two lengths, the same at any resolution).
  double unexplained_ratio() const;
  double explained_ratio() const;
  double wrong_percent() const { return 100.0 * wrong_fraction(); }
  // Sums the counts, keeps the largest region (for several lights: one verdict over all masks).
  MaskMetrics& operator+=(const MaskMetrics& other);
};

// A wrong region is structural (a thick core, not a boundary band) where it holds a whole 5 × 5 block
// of unexplained pixels. Why 5 and not 3: an exact technique's terminator on a faceted sphere, where a
// face and the shadow volume's side meet at a grazing angle, z-fights inside a wedge a few pixels wide
// at 1024² (measured: a 3 × 3 block, once, on ground_sphere); a 5 × 5 block is still far inside any
// blatant error (an 8 × 8 swapped tile holds 16 such cores at any resolution).
inline constexpr int kCoreRadius = 2;

// The window of MaskMetrics::densest_unexplained: 9 × 9 pixels, just over an 8 × 8 tile (the size of
// the local glitch a tiled GPU, a wrong texel fetch or a broken cache line leaves), so that one such
// tile fits whole in the window centred on any of its pixels near its middle.
inline constexpr int kClusterRadius = 4;

// The unexplained cores of a w × h image of flags (non-zero: unexplained), `flagged_count` of them:
// the flagged pixels whose whole (2 kCoreRadius + 1)² neighbourhood, inside the image, is flagged.
std::size_t count_cores(const std::vector<std::uint8_t>& flagged, int w, int h, std::size_t flagged_count);

// The most flagged pixels of a w × h image of flags in one (2 kClusterRadius + 1)² window centred on
// one of `listed` (the flagged pixels' indices, row-major), clipped to the image:
// MaskMetrics::densest_unexplained's count. Cost: one window per listed pixel.
std::size_t densest_window(const std::vector<std::uint8_t>& flagged, const std::vector<std::size_t>& listed, int w, int h);

struct MaskComparison {
  MaskMetrics metrics;
  Displacement displacement;  // looked for where options.displacement_up_to allows (metrics.displaced: its count)
  Image8 error;  // RGB: wrong pixels by kind or cause over the dimmed reference (outputs::kErrorClasses)
  std::vector<std::size_t> unexplained;  // the unexplained pixels' indices (row-major), where CompareOptions::list_unexplained
};

// The error image's colours and their meaning: outputs::kErrorClasses (outputs/cause.hpp), the one
// table the painter, the report, the pack's README and `compare --help` read.
using outputs::ErrorClass;
using outputs::error_colour;

// The causes a wrong decided pixel may have (the reference's cause model computes them).
using outputs::Cause;
// Asked, when the threshold has bands, for every wrong pixel (x, y) of light `light` that is
// decided (or judged by the scene's invariant): why may the candidate honestly answer `candidate_lit` there?
using Explainer = std::function<Cause(std::size_t light, int x, int y, bool candidate_lit)>;
// Asked once per mask, before any pixel is explained, with the reference and candidate masks of
// light `light` and the wrong pixels' indices (row-major): the wrong pixels that no correct render
// gives together, whatever each may be explained by alone (tolerance/zigzags.hpp: a shadow edge
// that zigzags faster than any texel grid allows). They count as unexplained (`impossible`).
using ImpossiblePixels = std::function<std::vector<std::size_t>(std::size_t light, const Image8& reference,
                                                                const Image8& candidate, const std::vector<std::size_t>& wrong)>;

struct CompareOptions {
  const Explainer* explain = nullptr;  // null: every wrong pixel is unexplained (exact techniques)
  const ImpossiblePixels* impossible = nullptr;  // null: none asked for
  // The scene's invariant holds on every surface pixel (the camera at the light sees no cast
  // shadow): undecided pixels where the reference is lit are judged too, for false shadows.
  bool no_cast_shadow_invariant = false;
  // Soft shadows (visibility.hpp): per light, the bounds of its lit fraction (a negative tolerance
  // where the light has no area: its fraction is the mask's). Empty: the technique's fraction is
  // not judged. Judged lights need visibility.png (visibility_<i>.png) from the candidate.
  std::vector<VisibilityBounds> visibility;
  const VisibilityExplainer* explain_visibility = nullptr;
  const VisibilityTexelShift* visibility_texel_shift = nullptr;  // null: the means get no texel shift
  // Displaced shadows (displacement.hpp) are looked for where the unexplained pixels are at most
  // this share of the edge pixels; negative: never. The judge's 1: looked for per light up to as many
  // unexplained pixels as edge pixels, since past its own fail bound a light may still sum to a total
  // below it beside a light with more edges (a mask wrong beyond that FAILs anyway).
  double displacement_up_to = 1.0;
  // Whether MaskComparison::error is painted. False: left empty (0 x 0), the counts the same; for
  // callers that read only the counts (the resolving power's probes), which then skip an RGB
  // image's allocation and its every-pixel write, most of a comparison's memory traffic.
  bool error_image = true;
  // Whether MaskComparison::unexplained lists the unexplained pixels: for a caller that judges parts
  // of one candidate apart (the resolving power's tile sweep), the counts alone being the whole's.
  bool list_unexplained = false;
};

// Compares one mask. All three images are 1-channel and of the same size; throws
// CompareError(SizeMismatch) naming both sizes otherwise (`what` names the files in messages), and
// CompareError(BadInput) for a candidate value other than the three, before anything is judged.
MaskComparison compare_mask(const Image8& reference, const Image8& decided, const Image8& candidate,
                            const std::string& what = "mask", std::size_t light = 0, const CompareOptions& options = {});

enum class Verdict { Pass, QualityWarning, Fail };
const char* to_string(Verdict v);  // "pass", "warning", "fail"

struct Decision {
  Verdict verdict = Verdict::Pass;
  std::vector<std::string> reasons;  // one line per bound exceeded, with the numbers; empty on pass
};

// The verdict of `metrics` against `threshold` (thresholds.hpp; displaced shadows against
// kDisplaced, `displaced_how` saying the moves in its reason): FAIL beyond a fail bound, a quality
// warning beyond a pass bound, PASS otherwise.
Decision decide(const MaskMetrics& metrics, const Threshold& threshold, const std::string& displaced_how = "");

// The verdict of a case of several lights: each light's mask decided alone (decide(), with its
// `displaced_how`), the worst of them, each reason led by the light's mask name (`names`). Summed
// over the lights, one light's displaced or unexplained pixels would be weighed against every
// light's edges, and one light's shadows moved by a pixel would pass beside three correct lights;
// decided alone they FAIL as in a scene of that light alone. The sum's own verdict is never worse
// (a ratio over the sum lies between the lights' ratios; cores and windows lie in one light's mask).
// One light: decide() itself, its reasons as they are.
Decision decide_lights(const std::vector<MaskMetrics>& lights, const Threshold& threshold,
                       const std::vector<std::string>& names, const std::vector<std::string>& displaced_how);

// A reference folder (mask.png or mask_<i>.png, decided.png or decided_<i>.png) against a
// candidate folder with the same mask names.
struct FolderComparison {
  std::vector<std::string> masks;          // mask file names, in light order
  std::vector<MaskComparison> per_light;   // same order
  MaskMetrics total;                       // summed over lights
  // Soft shadows: per light, the comparison of its lit fraction (nullopt: not judged), and the sum.
  std::vector<std::optional<VisibilityComparison>> visibility;
  std::optional<VisibilityMetrics> visibility_total;
  Decision decision;
  const Threshold* threshold = nullptr;
};

// What one comparison of a reference folder with a candidate folder reads, each image decoded once
// (read_folder_images), so that a judge that looks at the candidate more than once (its staircases,
// the comparison, the probes of the reference's own masks, the technique's model) reads no file twice.
struct FolderImages {
  std::vector<std::string> masks;                       // mask file names, in light order
  std::vector<Image8> reference, decided, candidate;    // per light
  std::vector<std::string> candidate_files;             // per light: the candidate mask's path, for messages
  // Soft shadows, per light whose lit fraction is judged (add_fractions): the reference's lit
  // fraction and the candidate's; `covered` (the reference's covered pixels) once for all of them.
  struct Fraction {
    std::vector<float> reference;
    Image8 candidate;
  };
  std::vector<std::optional<Fraction>> fractions;
  Image8 covered;
};

// The masks of `reference_dir` and `candidate_dir`: every check compare_folders makes of them, in
// its order (a stray or missing candidate mask, an unreadable file, a size mismatch). Throws
// CompareError as compare_folders does. Cost: three PNG decodes per light.
FolderImages read_folder_images(const std::filesystem::path& reference_dir, const std::filesystem::path& candidate_dir);

// Adds the lit fractions of the lights `options` judges them for (options.visibility[i].tolerance
// >= 0): the reference's visibility exr and covered.png, the candidate's visibility png. Throws
// CompareError for a missing, unreadable or mis-sized one. Cost: two decodes per such light, and one.
void add_fractions(FolderImages& images, const std::filesystem::path& reference_dir, const std::filesystem::path& candidate_dir,
                   const CompareOptions& options);

// The comparison of images already read (what compare_folders does after reading them).
FolderComparison compare_images(const FolderImages& images, const Threshold& threshold, const CompareOptions& options = {});

// Reads both folders (read_folder_images, add_fractions) and compares them (compare_images).
// Throws CompareError: BadInput for missing or unreadable files, a candidate lacking a mask the
// reference has; SizeMismatch when a candidate mask is not the reference's size.
FolderComparison compare_folders(const std::filesystem::path& reference_dir,
                                 const std::filesystem::path& candidate_dir, const Threshold& threshold,
                                 const CompareOptions& options = {});

// The verdict of a soft technique's fractions (thresholds.hpp, kPenumbra): FAIL on any unexplained
// core, or beyond the unexplained-ratio or mean-error bound; merged into `decision`.
void decide_visibility(const VisibilityMetrics& metrics, Decision& decision);

// Writes error.png (one light) or error_<i>.png into `dir`, and visibility_error.png
// (visibility_error_<i>.png) for judged fractions; returns the names written.
std::vector<std::string> write_error_images(const FolderComparison& c, const std::filesystem::path& dir);

}  // namespace shadowref::compare
