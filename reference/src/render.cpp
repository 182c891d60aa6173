// render.cpp — the reference renderer (render.hpp), shaped like the Embree tutorials: scene
// setup, a per-tile function (primary stream, shadow stream, gather), a parallel loop over tiles.
#include "shadowref/reference/render.hpp"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#ifdef SHADOWREF_PLAIN_THREADS
#include <atomic>
#include <thread>
#endif

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "shadowref/outputs/image.hpp"
#include "shadowref/outputs/interruption.hpp"
#include "shadowref/outputs/shading.hpp"
#include "shadowref/reference/flush_denormals.hpp"
#include "shadowref/reference/camera_rays.hpp"
#include "shadowref/reference/embree_scene.hpp"
#include "shadowref/reference/pixel_surface.hpp"
#include "shadowref/reference/ray_stream.hpp"
#include "shadowref/reference/shadow_ray.hpp"
#include "shadowref/scene/camera.hpp"
#include "shadowref/scene/prepared_scene.hpp"

namespace shadowref::reference {
namespace {

using Clock = std::chrono::steady_clock;

constexpr int kTile = 16;                  // 16 × 16 pixels: coherent streams, enough tiles to balance
constexpr int kNudge = 4;                  // the decided test's second start offset, in epsilons
const Vec3<double> kBackground(outputs::kBackground[0], outputs::kBackground[1], outputs::kBackground[2]);

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

struct LightSetup {
  const scene::Light* light = nullptr;
  Vec4<double> centre;                    // homogeneous(): what the mask is about
  std::vector<Vec4<double>> samples;      // light_samples()
};

// One thread's scratch, reused from tile to tile. A tile's samples are laid out centres first
// (one per pixel), then each pixel's sub-pixel grid; its shadow answers (`lit`) light by light:
// the centres at 1 and kNudge epsilons, then per light sample every sub-pixel sample.
struct TileBuffers {
  std::vector<float> u, v;            // the samples' image points
  RayStream primary, shadow;
  std::vector<float> px, py, pz, nx, ny, nz;  // the samples' surfaces (pixel_surface.hpp)
  SurfaceArrays arrays() { return {px.data(), py.data(), pz.data(), nx.data(), ny.data(), nz.data()}; }
  std::vector<std::uint8_t> lit;      // 1: lit
  std::vector<double> direct;         // per light, per sub-pixel sample: the Lambert sum over lit light samples
  std::vector<std::uint32_t> lit_count;  // per light, per sub-pixel sample: lit light samples
  std::vector<double> lit_sum;        // gather's per-light scratch, reused from pixel to pixel
  std::vector<std::uint8_t> agree;
  std::vector<std::size_t> light_base;    // where each light's answers start in `lit`
  std::vector<std::uint8_t> centre_lit;   // the pixel centre's answer per light (1 epsilon)
  Stats stats;
};

class Renderer {
 public:
  Renderer(const scene::PreparedScene& prepared, const Options& options, const EmbreeScene& embree, Images& out)
      : scene_(*prepared.scene), embree_(embree), out_(out), camera_(prepared), n_(options.samples_per_axis) {
    for (std::size_t i = 0; i < scene_.lights.size(); ++i)
      lights_.push_back({&scene_.lights[i], prepared.lights[i], light_samples(scene_.lights[i])});
    subs_ = static_cast<std::size_t>(n_ * n_);
    for (std::size_t s = 0; s < subs_; ++s) {
      const int i = static_cast<int>(s) % n_, j = static_cast<int>(s) / n_;
      sub_xf_.push_back(static_cast<float>((i + 0.5) / n_));
      sub_yf_.push_back(static_cast<float>((j + 0.5) / n_));
    }
    eps_ = embree.epsilon();
  }

  void tile(int x0, int y0, TileBuffers& buf) const {
    const int x1 = std::min(x0 + kTile, scene_.width), y1 = std::min(y0 + kTile, scene_.height);
    const std::size_t pixels = static_cast<std::size_t>((x1 - x0) * (y1 - y0));
    const std::size_t samples = pixels * (1 + subs_);
    FlushDenormalsGuard ftz;
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;

    // 1. Primary rays: the pixel centres, then each pixel's sub-pixel grid row by row.
    const auto rays0 = Clock::now();
    buf.u.resize(samples);
    buf.v.resize(samples);
    std::size_t k = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x, ++k) {
        buf.u[k] = CameraRays::image_point(x, 0.5);
        buf.v[k] = CameraRays::image_point(y, 0.5);
      }
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x, k += subs_) {
        // image_point(x, sx) for each sub-pixel position, the float offsets rounded once.
        const float fx = static_cast<float>(x), fy = static_cast<float>(y);
        float* __restrict u = buf.u.data() + k;
        float* __restrict v = buf.v.data() + k;
        for (std::size_t s = 0; s < subs_; ++s) {
          u[s] = fx + sub_xf_[s];
          v[s] = fy + sub_yf_[s];
        }
      }
    buf.primary.resize(samples);
    camera_.build(buf.u.data(), buf.v.data(), samples, buf.primary, 0);
    buf.primary.reset_hits();
    const auto primary0 = Clock::now();
    const RTCRayHitNp hits = buf.primary.ray_hits();
    rtcIntersectNp(embree_.handle(), &ctx, &hits, static_cast<unsigned>(samples));
    buf.stats.seconds_primary_calls += seconds_since(primary0);
    buf.stats.primary_rays += samples;

    // 2. Surfaces, in float (pixel_surface.hpp): the shadow rays' input, and the gather's.
    for (auto* a : {&buf.px, &buf.py, &buf.pz, &buf.nx, &buf.ny, &buf.nz}) a->resize(samples);
    hit_surfaces(buf.primary, 0, samples, buf.arrays());

    // 3. Shadow rays, light by light, in groups of at most one sub-pixel grid's worth (4096 rays at
    //    16 × 16 pixels and 4 × 4 samples: small enough for L2): the centres toward the light's centre at
    //    1 and kNudge epsilons, then every sub-pixel sample toward each light sample.
    const auto phase0 = Clock::now();
    const std::size_t sub_samples = pixels * subs_;
    const SurfacePoints centres{buf.px.data(), buf.py.data(), buf.pz.data(), buf.nx.data(), buf.ny.data(), buf.nz.data()};
    const SurfacePoints subs{buf.px.data() + pixels, buf.py.data() + pixels, buf.pz.data() + pixels,
                             buf.nx.data() + pixels, buf.ny.data() + pixels, buf.nz.data() + pixels};
    std::size_t total = 0;
    for (const auto& l : lights_) total += 2 * pixels + l.samples.size() * sub_samples;
    buf.lit.resize(total);
    std::size_t slot = 0;
    // The exported stage (shadow_ray.hpp), the one the benchmarks time; its time counts as inside
    // Embree's calls (reading the answers back, a byte a ray, is within its noise).
    const auto trace = [&](std::size_t count) {
      const auto calls0 = Clock::now();
      occlude_shadow_rays(embree_, buf.shadow, count, buf.lit.data() + slot);
      buf.stats.seconds_shadow_calls += seconds_since(calls0);
      buf.stats.shadow_rays += count;
      slot += count;
    };
    for (const auto& l : lights_) {
      buf.shadow.resize(2 * pixels);
      build_shadow_rays(centres, pixels, l.centre, eps_, buf.shadow, 0);
      build_shadow_rays(centres, pixels, l.centre, kNudge * eps_, buf.shadow, pixels);
      trace(2 * pixels);
      buf.shadow.resize(sub_samples);
      for (const auto& L : l.samples) {
        build_shadow_rays(subs, sub_samples, L, eps_, buf.shadow, 0);
        trace(sub_samples);
      }
    }
    buf.stats.seconds_ray_work += seconds_since(rays0);

    // 4. Shading's sums, light sample by light sample over all sub-pixel samples (shadow_ray.hpp).
    buf.direct.assign(lights_.size() * sub_samples, 0.0);
    buf.lit_count.assign(lights_.size() * sub_samples, 0);
    slot = 0;
    for (std::size_t li = 0; li < lights_.size(); ++li) {
      slot += 2 * pixels;
      for (const auto& L : lights_[li].samples) {
        accumulate_lit(subs, sub_samples, L, buf.lit.data() + slot, buf.direct.data() + li * sub_samples,
                       buf.lit_count.data() + li * sub_samples);
        slot += sub_samples;
      }
    }

    // 5. Gather, pixel by pixel.
    std::size_t pixel = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x, ++pixel) gather(x, y, pixel, pixels, buf);
    buf.stats.seconds_shadow_phase += seconds_since(phase0);
  }

 private:
  // The spot cone as a hard cut-off (1 inside, 0 outside); 1 for every other light type.
  static double cone(const scene::Light& l, const Vec3<double>& p) {
    if (l.type != scene::LightType::Spot) return 1.0;
    const Vec3<double> d = p - l.position;
    const double len = d.norm();
    if (!(len > 0)) return 1.0;
    return l.direction.dot(d) / len >= std::cos(l.cone_deg * std::numbers::pi / 180.0) ? 1.0 : 0.0;
  }

  // Pixel `pixel` of a tile of `pixels` (TileBuffers' layout) into the images.
  void gather(int x, int y, std::size_t pixel, std::size_t pixels, TileBuffers& buf) const {
    const std::size_t W = static_cast<std::size_t>(scene_.width);
    const std::size_t out = static_cast<std::size_t>(y) * W + static_cast<std::size_t>(x);
    const std::size_t sub_samples = pixels * subs_;
    const SurfaceArrays arrays = buf.arrays();
    const Surface c = surface_of(scene_, buf.primary, pixel, arrays, pixel);
    const double light_weight = outputs::kDirect / static_cast<double>(lights_.size());

    Vec3<double> colour = Vec3<double>::Zero();
    std::vector<double>& lit_sum = buf.lit_sum;  // no allocation per pixel
    std::vector<std::uint8_t>& agree = buf.agree;
    lit_sum.assign(lights_.size(), 0.0);
    agree.assign(lights_.size(), 1);
    // Where each light's answers start in buf.lit, and the centre's answers at 1 epsilon.
    std::size_t base = 0;
    buf.light_base.resize(lights_.size());
    buf.centre_lit.resize(lights_.size());
    for (std::size_t li = 0; li < lights_.size(); ++li) {
      buf.light_base[li] = base;
      buf.centre_lit[li] = c.hit && buf.lit[base + pixel];
      base += 2 * pixels + lights_[li].samples.size() * sub_samples;
    }
    int hits = 0;
    bool one_surface = true;  // "fully covered" (render.hpp, decided)
    for (std::size_t s = 0; s < subs_; ++s) {
      const std::size_t sample = pixels + pixel * subs_ + s;
      const Surface h = surface_of(scene_, buf.primary, sample, arrays, sample);
      if (h.hit != c.hit) std::fill(agree.begin(), agree.end(), std::uint8_t{0});
      if (!h.hit) {
        colour += kBackground;
        continue;
      }
      ++hits;
      if (c.hit && !same_smooth_surface(c, h, eps_)) one_surface = false;
      double radiance = outputs::kAmbient;
      for (std::size_t li = 0; li < lights_.size(); ++li) {
        const LightSetup& l = lights_[li];
        const std::size_t k = li * sub_samples + pixel * subs_ + s;
        const std::uint32_t lit_count = buf.lit_count[k];
        const double direct = buf.direct[k] * cone(*l.light, h.p);
        const double fraction = static_cast<double>(lit_count) / static_cast<double>(l.samples.size());
        lit_sum[li] += fraction;
        radiance += light_weight * direct / static_cast<double>(l.samples.size());
        if (fraction != (buf.centre_lit[li] ? 1.0 : 0.0)) agree[li] = 0;
      }
      colour += radiance * h.albedo.cast<double>();
    }

    const double samples = static_cast<double>(subs_);
    bool all_decided = true;
    float vis_sum = 0;
    for (std::size_t li = 0; li < lights_.size(); ++li) {
      LightImages& img = out_.lights[li];
      bool decided = agree[li] != 0 && one_surface;
      if (c.hit) {
        const bool lit1 = buf.lit[buf.light_base[li] + pixel] != 0;
        const bool lit4 = buf.lit[buf.light_base[li] + pixels + pixel] != 0;
        img.mask[out] = lit1 ? outputs::kMaskLit : outputs::kMaskShadowed;
        decided = decided && lit1 == lit4 && std::abs(facing(c.p, c.n, lights_[li].centre)) >= kGrazingCosine;
      } else {
        img.mask[out] = outputs::kMaskNoSurface;
      }
      img.visibility[out] = hits > 0 ? static_cast<float>(lit_sum[li] / hits) : -1.0f;
      img.decided[out] = decided ? outputs::kFlagSet : outputs::kFlagClear;
      all_decided = all_decided && decided;
      vis_sum += img.visibility[out];
    }
    out_.visibility[out] = hits > 0 ? vis_sum / static_cast<float>(lights_.size()) : -1.0f;
    out_.decided[out] = all_decided ? outputs::kFlagSet : outputs::kFlagClear;
    out_.covered[out] = c.hit && one_surface && hits == static_cast<int>(subs_) ? 255 : 0;
    colour /= samples;
    for (int ch = 0; ch < 3; ++ch) out_.shaded[3 * out + static_cast<std::size_t>(ch)] = outputs::encode_srgb8(colour[ch]);
  }

  const scene::Scene& scene_;
  const EmbreeScene& embree_;
  Images& out_;
  CameraRays camera_;
  int n_;
  std::vector<LightSetup> lights_;
  std::size_t subs_ = 0;               // sub-pixel samples per pixel: n_²
  std::vector<float> sub_xf_, sub_yf_;  // their positions in the pixel, row by row, rounded to float
  double eps_ = 0;
};

}  // namespace

Images render(const scene::Scene& scene, const Options& options, Stats* stats) {
  return render(scene::prepare_scene(scene), options, stats);
}

Images render(const scene::PreparedScene& prepared, const Options& options, Stats* stats) {
  const scene::Scene& scene = *prepared.scene;
  if (options.samples_per_axis < 1 || options.samples_per_axis > 16) throw std::invalid_argument("samples per axis must be in [1, 16]");
  if (options.threads < 0) throw std::invalid_argument("threads must be >= 0 (0: all cores)");
  Images img;
  img.width = scene.width;
  img.height = scene.height;
  const std::size_t n = static_cast<std::size_t>(scene.width) * static_cast<std::size_t>(scene.height);
  img.lights.resize(scene.lights.size());
  for (auto& l : img.lights) {
    l.mask.assign(n, outputs::kMaskNoSurface);
    l.visibility.assign(n, -1.0f);
    l.decided.assign(n, 0);
  }
  img.visibility.assign(n, -1.0f);
  img.decided.assign(n, 0);
  img.covered.assign(n, 0);
  img.shaded.assign(3 * n, 0);

  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  Stats total;
  arena.execute([&] {
    const auto t0 = Clock::now();
    std::optional<EmbreeScene> embree;
    {
      FlushDenormalsGuard ftz;  // the build runs on this thread too
      embree.emplace(scene, options.embree_config);
    }
    total.seconds_build = seconds_since(t0);
    const auto t1 = Clock::now();
    const Renderer renderer(prepared, options, *embree, img);
    const int tiles_x = (scene.width + kTile - 1) / kTile, tiles_y = (scene.height + kTile - 1) / kTile;
#ifndef SHADOWREF_PLAIN_THREADS
    tbb::enumerable_thread_specific<TileBuffers> buffers;
    tbb::parallel_for(tbb::blocked_range<int>(0, tiles_x * tiles_y, 1), [&](const tbb::blocked_range<int>& r) {
      TileBuffers& buf = buffers.local();
      for (int t = r.begin(); t < r.end(); ++t) {
        // SIGINT / SIGTERM: one tile's work at most (TBB cancels the other tiles and rethrows here).
        outputs::throw_if_interrupted();
        renderer.tile((t % tiles_x) * kTile, (t / tiles_x) * kTile, buf);
      }
    });
#else
    // The ThreadSanitizer build (preset tsan): the same tiles on plain std::threads taking tile
    // numbers from one atomic counter, each with its own buffers. Debian's libtbb is not
    // instrumented, so TSan cannot see its hand-offs and would report every TBB task as a race;
    // threads it can see leave only the races of our own code to report.
    const int workers = options.threads > 0 ? options.threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    std::vector<TileBuffers> buffers(static_cast<std::size_t>(workers));
    std::atomic<int> next{0};
    std::vector<std::thread> pool;
    for (int w = 0; w < workers; ++w)
      pool.emplace_back([&, w] {
        // An exception may not leave a std::thread: a signalled worker stops, the join rethrows.
        for (int t; !outputs::interrupt_signal() && (t = next.fetch_add(1)) < tiles_x * tiles_y;)
          renderer.tile((t % tiles_x) * kTile, (t / tiles_x) * kTile, buffers[static_cast<std::size_t>(w)]);
      });
    for (std::thread& t : pool) t.join();
    outputs::throw_if_interrupted();
#endif
    total.seconds_render = seconds_since(t1);
    for (const auto& b : buffers) {
      total.primary_rays += b.stats.primary_rays;
      total.shadow_rays += b.stats.shadow_rays;
      total.seconds_shadow_calls += b.stats.seconds_shadow_calls;
      total.seconds_shadow_phase += b.stats.seconds_shadow_phase;
      total.seconds_primary_calls += b.stats.seconds_primary_calls;
      total.seconds_ray_work += b.stats.seconds_ray_work;
    }
  });
  if (stats) *stats = total;
  return img;
}

}  // namespace shadowref::reference
