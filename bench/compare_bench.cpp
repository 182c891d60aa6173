// compare_bench.cpp — our mask comparison (compare_mask: decided pixels only, wrong pixels by kind,
// 8-connected regions, the error image) against OpenImageIO's ImageBufAlgo::compare (per-pixel
// differences and their statistics) on the same pair of 2048² 8-bit grey masks; and ours with the
// displaced-shadow search on; ours without the error image (the counts alone, as the resolving
// power's probes compare); and the streaming floor: one pass that reads the three images and counts
// the decided pixels whose mask differs, what any comparison of them must at least do.
#include <benchmark/benchmark.h>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <cstdint>

#include "bench_support.hpp"
#include "shadowref/compare/compare.hpp"

namespace {

namespace cmp = shadowref::compare;
constexpr int kSide = 2048;

// A reference mask (a disc of shadow on a lit floor, background at the top), its decided image
// (undecided along the disc's rim) and a candidate whose disc is shifted by two pixels.
struct Pair {
  cmp::Image8 reference, decided, candidate;
  Pair() {
    for (cmp::Image8* im : {&reference, &decided, &candidate}) {
      im->width = im->height = kSide;
      im->channels = 1;
      im->pixels.assign(static_cast<std::size_t>(kSide) * kSide, 0);
    }
    auto value = [](int x, int y, int cx) -> std::uint8_t {
      if (y < kSide / 8) return 128;
      const int dx = x - cx, dy = y - kSide / 2;
      return dx * dx + dy * dy < (kSide / 4) * (kSide / 4) ? 0 : 255;
    };
    for (int y = 0; y < kSide; ++y)
      for (int x = 0; x < kSide; ++x) {
        const auto i = static_cast<std::size_t>(y) * kSide + static_cast<std::size_t>(x);
        reference.pixels[i] = value(x, y, kSide / 2);
        candidate.pixels[i] = value(x, y, kSide / 2 + 2);
        const int dx = x - kSide / 2, dy = y - kSide / 2, r2 = dx * dx + dy * dy, r = kSide / 4;
        decided.pixels[i] = (r2 > (r - 1) * (r - 1) && r2 < (r + 1) * (r + 1)) ? 0 : 255;
      }
  }
};

const Pair& pair() {
  static const Pair p;
  return p;
}

void finish(benchmark::State& state) {
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * kSide * kSide);
  state.counters["pixels_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * kSide * kSide, benchmark::Counter::kIsRate);
  shadowref::bench::report_peak_rss(state);
}

void BM_MaskCompare_Ours(benchmark::State& state) {
  const Pair& p = pair();
  for (auto _ : state) {
    const cmp::MaskComparison c = cmp::compare_mask(p.reference, p.decided, p.candidate);
    benchmark::DoNotOptimize(c.metrics.wrong);
  }
  finish(state);
}
BENCHMARK(BM_MaskCompare_Ours)->Arg(1)->ArgName("threads")->UseRealTime()->Unit(benchmark::kMillisecond)->Setup(shadowref::bench::start_peak_rss);

// The same comparison with the displaced-shadow search on (displacement.hpp), as compare_folders
// runs it: what the search adds.
void BM_MaskCompare_Displaced(benchmark::State& state) {
  const Pair& p = pair();
  cmp::CompareOptions o;
  o.displacement_up_to = 1.0;
  for (auto _ : state) {
    const cmp::MaskComparison c = cmp::compare_mask(p.reference, p.decided, p.candidate, "mask", 0, o);
    benchmark::DoNotOptimize(c.metrics.displaced);
  }
  finish(state);
}
BENCHMARK(BM_MaskCompare_Displaced)->Arg(1)->ArgName("threads")->UseRealTime()->Unit(benchmark::kMillisecond)->Setup(shadowref::bench::start_peak_rss);

void BM_MaskCompare_Counts(benchmark::State& state) {
  const Pair& p = pair();
  cmp::CompareOptions o;
  o.error_image = false;
  for (auto _ : state) {
    const cmp::MaskComparison c = cmp::compare_mask(p.reference, p.decided, p.candidate, "mask", 0, o);
    benchmark::DoNotOptimize(c.metrics.wrong);
  }
  finish(state);
}
BENCHMARK(BM_MaskCompare_Counts)->Arg(1)->ArgName("threads")->UseRealTime()->Unit(benchmark::kMillisecond)->Setup(shadowref::bench::start_peak_rss);

// The floor: the three images read once, a byte compare and a count (vectorised by the compiler).
void BM_MaskCompare_Floor(benchmark::State& state) {
  const Pair& p = pair();
  const std::size_t n = p.reference.pixels.size();
  for (auto _ : state) {
    const std::uint8_t* __restrict r = p.reference.pixels.data();
    const std::uint8_t* __restrict d = p.decided.pixels.data();
    const std::uint8_t* __restrict c = p.candidate.pixels.data();
    std::size_t wrong = 0;
    for (std::size_t i = 0; i < n; ++i) wrong += static_cast<std::size_t>((r[i] != c[i]) & (d[i] == 255));
    benchmark::DoNotOptimize(wrong);
  }
  finish(state);
}
BENCHMARK(BM_MaskCompare_Floor)->Arg(1)->ArgName("threads")->UseRealTime()->Unit(benchmark::kMillisecond)->Setup(shadowref::bench::start_peak_rss);

void BM_MaskCompare_OIIO(benchmark::State& state) {
  const Pair& p = pair();
  const OIIO::ImageSpec spec(kSide, kSide, 1, OIIO::TypeDesc::UINT8);
  // ImageBuf wrapping caller memory (no copy): const_cast because the wrapping constructor takes
  // void*; compare() only reads.
  const OIIO::ImageBuf a(spec, const_cast<std::uint8_t*>(p.reference.pixels.data()));
  const OIIO::ImageBuf b(spec, const_cast<std::uint8_t*>(p.candidate.pixels.data()));
  for (auto _ : state) {
    const auto r = OIIO::ImageBufAlgo::compare(a, b, 0.5f, 0.5f, OIIO::ROI::All(), static_cast<int>(state.range(0)));
    benchmark::DoNotOptimize(r.nfail);
  }
  finish(state);
}
// threads:1 is the like-for-like peer (ours runs on one thread); threads:0 is OIIO's default (all).
BENCHMARK(BM_MaskCompare_OIIO)->Arg(1)->Arg(0)->ArgName("threads")->UseRealTime()->Unit(benchmark::kMillisecond)->Setup(shadowref::bench::start_peak_rss);

}  // namespace

BENCHMARK_MAIN();
