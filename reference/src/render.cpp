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
#include <xmmintrin.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "shadowref/outputs/image.hpp"
#include "shadowref/outputs/shading.hpp"
#include "shadowref/reference/embree_scene.hpp"
#include "shadowref/reference/pixel_surface.hpp"
#include "shadowref/reference/shadow_ray.hpp"
#include "shadowref/scene/camera.hpp"
#include "shadowref/scene/prepared_scene.hpp"

namespace shadowref::reference {
namespace {

using Clock = std::chrono::steady_clock;

constexpr int kTile = 16;                  // 16 × 16 pixels: coherent streams, enough tiles to balance
constexpr std::size_t kStreamChunk = 4096; // rays per rtcOccluded1M call: big enough to amortise, small enough for L2
constexpr int kNudge = 4;                  // the decided test's second start offset, in epsilons
constexpr std::int32_t kSlotShadowed = -1; // attached shadow: no ray
constexpr std::int32_t kSlotLit = -2;      // light touching the surface: no ray
const Vec3<double> kBackground(outputs::kBackground[0], outputs::kBackground[1], outputs::kBackground[2]);

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Embree asks for flush-to-zero and denormals-are-zero on the threads that trace (docs/dependencies.md);
// the mode is per thread and changes other float results there, so it is set for one tile and
// restored after, leaving TBB's worker threads as we found them.
class FlushDenormalsGuard {
 public:
  FlushDenormalsGuard() : saved_(_mm_getcsr()) { _mm_setcsr(saved_ | 0x8040u); }  // FTZ (bit 15) | DAZ (bit 6)
  ~FlushDenormalsGuard() { _mm_setcsr(saved_); }
  FlushDenormalsGuard(const FlushDenormalsGuard&) = delete;
  FlushDenormalsGuard& operator=(const FlushDenormalsGuard&) = delete;

 private:
  unsigned saved_;
};


struct LightSetup {
  const scene::Light* light = nullptr;
  Vec4<double> centre;                    // homogeneous(): what the mask is about
  std::vector<Vec4<double>> samples;      // light_samples()
};

struct TileBuffers {
  std::vector<RTCRayHit> primary;
  std::vector<Surface> surfaces;
  std::vector<std::int32_t> slots;
  std::vector<RTCRay> shadow;
  std::vector<double> lit_sum;        // gather's per-light scratch, reused from pixel to pixel
  std::vector<std::uint8_t> agree;
  Stats stats;
};

class Renderer {
 public:
  Renderer(const scene::PreparedScene& prepared, const Options& options, const EmbreeScene& embree, Images& out)
      : prepared_(prepared), scene_(*prepared.scene), embree_(embree), out_(out), n_(options.samples_per_axis) {
    // The prepared scene's camera, in its run convention: the very matrices the renderer draws with.
    inverse_view_proj_ = prepared.camera.clip_from_scene.inverse();
    near_ndc_ = near_ndc_z(*prepared.convention);
    far_ndc_ = far_ndc_z(*prepared.convention);
    for (std::size_t i = 0; i < scene_.lights.size(); ++i)
      lights_.push_back({&scene_.lights[i], prepared.lights[i], light_samples(scene_.lights[i])});
    sub_slots_ = 0;
    for (const auto& l : lights_) sub_slots_ += l.samples.size();
    centre_slots_ = 2 * lights_.size();
    samples_per_pixel_ = 1 + static_cast<std::size_t>(n_ * n_);
    eps_ = embree.epsilon();
  }

  void tile(int x0, int y0, TileBuffers& buf) const {
    const int x1 = std::min(x0 + kTile, scene_.width), y1 = std::min(y0 + kTile, scene_.height);
    const std::size_t pixels = static_cast<std::size_t>((x1 - x0) * (y1 - y0));
    const std::size_t samples = pixels * samples_per_pixel_;
    FlushDenormalsGuard ftz;
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;

    // 1. Primary rays, pixel by pixel, centre first, then the sub-pixel grid row by row.
    const auto rays0 = Clock::now();
    buf.primary.resize(samples);
    std::size_t k = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x)
        for (std::size_t s = 0; s < samples_per_pixel_; ++s) primary_ray(x, y, s, buf.primary[k++]);
    const auto primary0 = Clock::now();
    rtcIntersect1M(embree_.handle(), &ctx, buf.primary.data(), static_cast<unsigned>(samples), sizeof(RTCRayHit));
    buf.stats.seconds_primary_calls += seconds_since(primary0);
    buf.stats.primary_rays += samples;

    // 2. Surfaces, in double, from the barycentrics (so p lies on the triangle to double precision).
    buf.surfaces.resize(samples);
    for (std::size_t i = 0; i < samples; ++i) buf.surfaces[i] = surface(buf.primary[i]);

    // 3. Shadow rays: per sample, per light, its slots (centre: 1 and kNudge epsilons toward the
    //    light's centre; sub-pixel samples: every light sample).
    const auto phase0 = Clock::now();
    const std::size_t slots_per_pixel = centre_slots_ + (samples_per_pixel_ - 1) * sub_slots_;
    buf.slots.assign(pixels * slots_per_pixel, kSlotShadowed);
    buf.shadow.clear();
    std::size_t slot = 0;
    for (std::size_t i = 0; i < samples; ++i) {
      const Surface& s = buf.surfaces[i];
      const bool centre = i % samples_per_pixel_ == 0;
      for (const auto& l : lights_) {
        if (centre) {
          for (const double offset : {eps_, kNudge * eps_}) buf.slots[slot++] = add_ray(s, l.centre, offset, buf.shadow);
        } else {
          for (const auto& L : l.samples) buf.slots[slot++] = add_ray(s, L, eps_, buf.shadow);
        }
      }
    }
    const auto calls0 = Clock::now();
    for (std::size_t first = 0; first < buf.shadow.size(); first += kStreamChunk) {
      const std::size_t count = std::min(kStreamChunk, buf.shadow.size() - first);
      rtcOccluded1M(embree_.handle(), &ctx, buf.shadow.data() + first, static_cast<unsigned>(count), sizeof(RTCRay));
    }
    buf.stats.seconds_shadow_calls += seconds_since(calls0);
    buf.stats.seconds_ray_work += seconds_since(rays0);
    buf.stats.shadow_rays += buf.shadow.size();

    // 4. Gather, pixel by pixel.
    std::size_t pixel = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x, ++pixel) gather(x, y, pixel, buf);
    buf.stats.seconds_shadow_phase += seconds_since(phase0);
  }

 private:
  void primary_ray(int x, int y, std::size_t s, RTCRayHit& rh) const {
    double sx = 0.5, sy = 0.5;
    if (s > 0) {
      const int i = static_cast<int>(s - 1) % n_, j = static_cast<int>(s - 1) / n_;
      sx = (i + 0.5) / n_;
      sy = (j + 0.5) / n_;
    }
    pixel_ray(prepared_, inverse_view_proj_, x, y, sx, sy, rh);
  }

  Surface surface(const RTCRayHit& rh) const { return surface_of(scene_, rh); }

  static std::int32_t add_ray(const Surface& s, const Vec4<double>& L, double offset, std::vector<RTCRay>& rays) {
    if (!s.hit) return kSlotShadowed;  // never read
    rays.emplace_back();  // the ray is built in its stream slot (shadow_ray.hpp: no copy)
    const ShadowRayKind kind = make_shadow_ray(s.p, s.n, L, offset, rays.back());
    if (kind == ShadowRayKind::Trace) return static_cast<std::int32_t>(rays.size() - 1);
    rays.pop_back();
    return kind == ShadowRayKind::Attached ? kSlotShadowed : kSlotLit;
  }

  static bool slot_lit(std::int32_t slot, const std::vector<RTCRay>& rays) {
    if (slot == kSlotShadowed) return false;
    if (slot == kSlotLit) return true;
    return !(rays[static_cast<std::size_t>(slot)].tfar < 0);  // Embree sets tfar to −inf on a hit
  }

  // The spot cone as a hard cut-off (1 inside, 0 outside); 1 for every other light type.
  static double cone(const scene::Light& l, const Vec3<double>& p) {
    if (l.type != scene::LightType::Spot) return 1.0;
    const Vec3<double> d = p - l.position;
    const double len = d.norm();
    if (!(len > 0)) return 1.0;
    return l.direction.dot(d) / len >= std::cos(l.cone_deg * std::numbers::pi / 180.0) ? 1.0 : 0.0;
  }

  void gather(int x, int y, std::size_t pixel, TileBuffers& buf) const {
    const std::size_t W = static_cast<std::size_t>(scene_.width);
    const std::size_t out = static_cast<std::size_t>(y) * W + static_cast<std::size_t>(x);
    const std::size_t first_sample = pixel * samples_per_pixel_;
    const std::size_t slots_per_pixel = centre_slots_ + (samples_per_pixel_ - 1) * sub_slots_;
    const std::int32_t* slots = buf.slots.data() + pixel * slots_per_pixel;
    const Surface& c = buf.surfaces[first_sample];
    const double light_weight = outputs::kDirect / static_cast<double>(lights_.size());

    Vec3<double> colour = Vec3<double>::Zero();
    std::vector<double>& lit_sum = buf.lit_sum;  // no allocation per pixel
    std::vector<std::uint8_t>& agree = buf.agree;
    lit_sum.assign(lights_.size(), 0.0);
    agree.assign(lights_.size(), 1);
    int hits = 0;
    bool one_surface = true;  // "fully covered" (render.hpp, decided)
    // Sub-pixel samples: their slots follow the centre's.
    const std::int32_t* sub = slots + centre_slots_;
    for (std::size_t s = 1; s < samples_per_pixel_; ++s) {
      const Surface& h = buf.surfaces[first_sample + s];
      if (h.hit != c.hit) std::fill(agree.begin(), agree.end(), std::uint8_t{0});
      if (!h.hit) {
        colour += kBackground;
        sub += sub_slots_;
        continue;
      }
      ++hits;
      if (c.hit && !same_smooth_surface(c, h, eps_)) one_surface = false;
      double radiance = outputs::kAmbient;
      for (std::size_t li = 0; li < lights_.size(); ++li) {
        const LightSetup& l = lights_[li];
        int lit_count = 0;
        double direct = 0;
        for (const auto& L : l.samples) {
          if (slot_lit(*sub++, buf.shadow)) {
            ++lit_count;
            direct += std::max(0.0, facing(h.p, h.n, L)) * cone(*l.light, h.p);
          }
        }
        const double fraction = static_cast<double>(lit_count) / static_cast<double>(l.samples.size());
        lit_sum[li] += fraction;
        radiance += light_weight * direct / static_cast<double>(l.samples.size());
        const bool centre_lit = c.hit && slot_lit(slots[2 * li], buf.shadow);
        if (fraction != (centre_lit ? 1.0 : 0.0)) agree[li] = 0;
      }
      colour += radiance * h.albedo.cast<double>();
    }

    const double samples = static_cast<double>(samples_per_pixel_ - 1);
    bool all_decided = true;
    float vis_sum = 0;
    for (std::size_t li = 0; li < lights_.size(); ++li) {
      LightImages& img = out_.lights[li];
      bool decided = agree[li] != 0 && one_surface;
      if (c.hit) {
        const bool lit1 = slot_lit(slots[2 * li], buf.shadow);
        const bool lit4 = slot_lit(slots[2 * li + 1], buf.shadow);
        img.mask[out] = lit1 ? outputs::kMaskLit : outputs::kMaskShadowed;
        decided = decided && lit1 == lit4 && std::abs(facing(c.p, c.n, lights_[li].centre)) >= kGrazingCosine;
      } else {
        img.mask[out] = outputs::kMaskNoSurface;
      }
      img.visibility[out] = hits > 0 ? static_cast<float>(lit_sum[li] / hits) : -1.0f;
      img.decided[out] = decided ? 255 : 0;
      all_decided = all_decided && decided;
      vis_sum += img.visibility[out];
    }
    out_.visibility[out] = hits > 0 ? vis_sum / static_cast<float>(lights_.size()) : -1.0f;
    out_.decided[out] = all_decided ? 255 : 0;
    out_.covered[out] = c.hit && one_surface && hits == static_cast<int>(samples_per_pixel_ - 1) ? 255 : 0;
    colour /= samples;
    for (int ch = 0; ch < 3; ++ch) out_.shaded[3 * out + static_cast<std::size_t>(ch)] = outputs::encode_srgb8(colour[ch]);
  }

  const scene::PreparedScene& prepared_;
  const scene::Scene& scene_;
  const EmbreeScene& embree_;
  Images& out_;
  int n_;
  Mat4<double> inverse_view_proj_;
  double near_ndc_ = -1, far_ndc_ = 1;  // clip-space z of the near and far planes (convention.hpp)
  std::vector<LightSetup> lights_;
  std::size_t sub_slots_ = 0;
  std::size_t centre_slots_ = 0;
  std::size_t samples_per_pixel_ = 1;
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
      embree.emplace(scene);
    }
    total.seconds_build = seconds_since(t0);
    const auto t1 = Clock::now();
    const Renderer renderer(prepared, options, *embree, img);
    const int tiles_x = (scene.width + kTile - 1) / kTile, tiles_y = (scene.height + kTile - 1) / kTile;
#ifndef SHADOWREF_PLAIN_THREADS
    tbb::enumerable_thread_specific<TileBuffers> buffers;
    tbb::parallel_for(tbb::blocked_range<int>(0, tiles_x * tiles_y, 1), [&](const tbb::blocked_range<int>& r) {
      TileBuffers& buf = buffers.local();
      for (int t = r.begin(); t < r.end(); ++t) renderer.tile((t % tiles_x) * kTile, (t / tiles_x) * kTile, buf);
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
        for (int t; (t = next.fetch_add(1)) < tiles_x * tiles_y;)
          renderer.tile((t % tiles_x) * kTile, (t / tiles_x) * kTile, buffers[static_cast<std::size_t>(w)]);
      });
    for (std::thread& t : pool) t.join();
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
