#include "dyngi/gi/path_tracer.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <unordered_map>

#include "dyngi/engine/scene/light_units.h"
#include "dyngi/gi/job_pool.h"
#include "bvh/scene_surfaces.h"
#include "indirect/emitters.h"
#include "sampling.h"

namespace dyngi::gi {

const OptionTable<PathTracerSettings>& PathTracerSettings::table() {
  static const OptionTable<PathTracerSettings> t =
      OptionTable<PathTracerSettings>()
          .add(DYNGI_OPTION(PathTracerSettings, spp), "path tracer samples per pixel", 1, 1000000)
          .add(DYNGI_OPTION(PathTracerSettings, bounces), "indirect bounces (0: direct light only)", 0, 64)
          .add(DYNGI_OPTION(PathTracerSettings, seed), "seed of the path tracer's random numbers", 0, 4294967295.0)
          .add(DYNGI_OPTION(PathTracerSettings, pixelJitter), "samples spread over the pixel (off: through its centre, as the rasterizer samples: the reference for a GI image)", 0, 1)
          .add(DYNGI_OPTION(PathTracerSettings, emitterSampling), "emissive triangles sampled as lights, by power, with MIS against the bounce (off: found by bounces only)", 0, 1);
  return t;
}
namespace {

constexpr float kPi = 3.14159265358979f;

// PCG32 (O'Neill): small, fast, good enough for Monte Carlo.
struct Rng {
  uint64_t state;
  uint64_t inc;
  Rng(uint64_t seed, uint64_t stream) : state(0), inc((stream << 1u) | 1u) {
    next();
    state += seed;
    next();
  }
  uint32_t next() {
    uint64_t old = state;
    state = old * 6364136223846793005ULL + inc;
    uint32_t xorshifted = uint32_t(((old >> 18u) ^ old) >> 27u);
    uint32_t rot = uint32_t(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32 - rot) & 31));
  }
  float uniform() { return float(next() >> 8) * (1.0f / 16777216.0f); }
};



class Tracer {
 public:
  Tracer(const render::RenderSnapshot& s, const EmbreeScene& bvh, const scene::AssetStore& assets, const PathTracerSettings& st)
      : snap_(s), bvh_(bvh), surfaces_(s, assets), emitters_(s, assets), settings_(st), sceneScale_(surfaces_.sceneScale()),
        sampleEmitters_(st.emitterSampling && !emitters_.empty()) {}

  glm::vec3 radiance(glm::vec3 origin, glm::vec3 dir, Rng& rng) const {
    glm::vec3 L(0.0f), throughput(1.0f);
    float bouncePdf = 0.0f;  // solid-angle density of the bounce that found this hit; 0: the camera ray
    for (uint32_t depth = 0;; ++depth) {
      RayHit h = bvh_.intersect(origin, dir, 0.0f, 1e30f);
      if (!h.hit) {
        L += throughput * settings_.background;
        break;
      }
      SurfaceHit sh;
      if (!surfaces_.at(h, origin, dir, sh)) break;
      if (sh.emission != glm::vec3(0.0f)) L += throughput * sh.emission * bounceWeight(h, sh, dir, bouncePdf);
      if (glm::dot(sh.diffuseAlbedo, sh.diffuseAlbedo) <= 0.0f) break;
      L += throughput * directLight(sh);
      if (depth >= settings_.bounces) break;
      // The emitters' light here is what the next hit's emission would add: sampled now, weighted by MIS.
      if (sampleEmitters_) L += throughput * emitterLight(sh, rng);
      // Cosine-weighted bounce: the Lambert BRDF (albedo/pi) x cos / pdf (cos/pi) = albedo.
      throughput *= sh.diffuseAlbedo;
      if (depth + 1 >= settings_.rouletteAfter) {
        float p = std::min(0.95f, std::max({throughput.r, throughput.g, throughput.b}));
        if (p <= 0.0f || rng.uniform() >= p) break;
        throughput /= p;
      }
      dir = cosineSample(sh.shadingNormal, rng);
      if (glm::dot(dir, sh.geometricNormal) <= 0.0f) break;  // shading normal tilted below the surface
      bouncePdf = std::max(glm::dot(dir, sh.shadingNormal), 0.0f) / kPi;
      origin = offset(sh);
    }
    return L;
  }

 private:
  glm::vec3 offset(const SurfaceHit& sh) const { return sh.position + sh.geometricNormal * (1e-4f * sceneScale_); }

  static glm::vec3 cosineSample(const glm::vec3& n, Rng& rng) {
    float u1 = rng.uniform(), u2 = rng.uniform();
    return cosineDirection(n, u1, u2);
  }

  // Power heuristic (Veach): the share of a contribution that the strategy with density `a` keeps.
  static float powerHeuristic(float a, float b) { return a * a / (a * a + b * b); }

  // The weight of emission found by a bounce, against emitter sampling finding the same point.
  float bounceWeight(const RayHit& h, const SurfaceHit& sh, const glm::vec3& dir, float bouncePdf) const {
    if (!sampleEmitters_ || bouncePdf <= 0.0f) return 1.0f;
    const float cosY = std::abs(glm::dot(sh.geometricNormal, dir));
    const float pdfArea = emitters_.pdfArea(h.entity, h.primitive);
    if (pdfArea <= 0.0f || cosY <= 0.0f) return 1.0f;
    return powerHeuristic(bouncePdf, pdfArea * h.t * h.t / cosY);
  }

  // One point on the emitters, chosen by power: its light on `sh`, shadowed, weighted against the bounce.
  glm::vec3 emitterLight(const SurfaceHit& sh, Rng& rng) const {
    const float u0 = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
    const EmitterSample e = emitters_.sample(u0, u1, u2, 0.0f);
    if (!(e.pdfArea > 0.0f)) return glm::vec3(0.0f);
    const glm::vec3 to = e.position - sh.position;
    const float d2 = glm::dot(to, to);
    if (!(d2 > 0.0f)) return glm::vec3(0.0f);
    const glm::vec3 wi = to / std::sqrt(d2);
    const float cosX = glm::dot(sh.shadingNormal, wi), cosY = std::abs(glm::dot(e.faceNormal, wi));
    // Directions the bounce cannot take (below either normal) carry no light here either.
    if (cosX <= 0.0f || glm::dot(sh.geometricNormal, wi) <= 0.0f || cosY <= 1e-6f) return glm::vec3(0.0f);
    if (bvh_.occluded(Segment{offset(sh), e.position}, 1e-4f * sceneScale_)) return glm::vec3(0.0f);
    const float pdfLight = e.pdfArea * d2 / cosY;  // per solid angle at sh
    const float weight = powerHeuristic(pdfLight, cosX / kPi);
    return sh.diffuseAlbedo / kPi * e.radiance * (cosX * weight / pdfLight);
  }

  glm::vec3 directLight(const SurfaceHit& sh) const {
    glm::vec3 sum(0.0f);
    glm::vec3 from = offset(sh);
    for (const render::LightItem& li : snap_.lights) {
      glm::vec3 e = scene::directIrradiance(li.light, li.position, li.direction, sh.position, sh.shadingNormal);
      if (e.r + e.g + e.b <= 0.0f) continue;
      glm::vec3 to = li.light.type == scene::LightType::Directional ? sh.position - li.direction * (4.0f * sceneScale_ + 1.0f) : li.position;
      if (li.light.castShadows && bvh_.occluded(Segment{from, to}, 1e-5f * sceneScale_)) continue;
      sum += sh.diffuseAlbedo / kPi * e;
    }
    return sum;
  }

  const render::RenderSnapshot& snap_;
  const EmbreeScene& bvh_;
  SceneSurfaces surfaces_;
  EmitterSet emitters_;
  PathTracerSettings settings_;
  float sceneScale_ = 1.0f;
  bool sampleEmitters_ = false;
};

}  // namespace

render::ImageRgba pathTrace(const render::RenderSnapshot& snapshot, const EmbreeScene& bvh, const scene::AssetStore& assets,
                            uint32_t width, uint32_t height, const PathTracerSettings& settings, PathTracerStats* stats,
                            const PathTracerProgress& progress) {
  auto t0 = std::chrono::steady_clock::now();
  render::ImageRgba accum(size_t(width) * height, glm::vec4(0.0f));
  if (width == 0 || height == 0) return accum;
  Tracer tracer(snapshot, bvh, assets, settings);
  glm::mat4 proj = snapshot.camera.projection(float(width) / float(height));
  glm::mat4 invViewProj = glm::inverse(proj * snapshot.camera.view);
  const glm::vec3 eye = snapshot.camera.position;
  const uint32_t spp = std::max(1u, settings.spp);

  for (uint32_t pass = 0; pass < spp; ++pass) {
    // Rows on the job pool; each pixel's random sequence depends on (seed, pass, pixel) only, so the
    // image does not depend on how rows are split among threads.
    parallelFor(0, height, 1, [&](size_t rowBegin, size_t rowEnd) {
      for (uint32_t y = uint32_t(rowBegin); y < rowEnd; ++y) {
        for (uint32_t x = 0; x < width; ++x) {
          size_t idx = size_t(y) * width + x;
          Rng rng(mix64(settings.seed * 0x9E3779B97F4A7C15ULL + pass), idx);
          float jx = rng.uniform(), jy = rng.uniform();
          if (!settings.pixelJitter) jx = jy = 0.5f;
          glm::vec4 ndc((float(x) + jx) / float(width) * 2.0f - 1.0f, (float(y) + jy) / float(height) * 2.0f - 1.0f, 1.0f, 1.0f);
          glm::vec4 farPoint = invViewProj * ndc;
          glm::vec3 dir = glm::normalize(glm::vec3(farPoint) / farPoint.w - eye);
          glm::vec3 L = tracer.radiance(eye, dir, rng);
          if (!std::isfinite(L.r) || !std::isfinite(L.g) || !std::isfinite(L.b)) L = glm::vec3(0.0f);
          accum[idx] += glm::vec4(L, 1.0f);
        }
      }
    }, settings.threads);
    if (progress) progress(pass + 1, spp);
  }
  for (auto& p : accum) p = glm::vec4(glm::vec3(p) / float(spp), 1.0f);
  if (stats) {
    stats->ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    stats->samples = uint64_t(width) * height * spp;
    stats->samplesPerSecond = stats->ms > 0 ? double(stats->samples) / (stats->ms * 1e-3) : 0.0;
  }
  return accum;
}

}  // namespace dyngi::gi
