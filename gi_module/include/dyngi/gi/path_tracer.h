#pragma once
// The reference: a CPU path tracer over the same Embree scene, camera, lights, materials and light units
// as the rasterizer. Lambert diffuse (base colour x texture x (1 - metallic)), emissive surfaces,
// punctual lights by next-event estimation, emissive triangles too (sampled by power, weighted against
// the bounce that may hit them by multiple importance sampling), cosine-sampled bounces, Russian roulette
// after a few. An emitter's light on a surface counts as one bounce, as the VPL techniques count it.
// `bounces` counts indirect bounces: 0 = emission + direct light, 1 = plus one indirect bounce, ...
#include <cstdint>
#include <functional>

#include "dyngi/engine/render/image_metrics.h"
#include "dyngi/engine/render/snapshot.h"
#include "dyngi/gi/bvh.h"
#include "dyngi/gi/options.h"

namespace dyngi::gi {

struct PathTracerSettings {
  uint32_t spp = 64;
  uint32_t bounces = 1;
  uint32_t rouletteAfter = 3;   // bounces before Russian roulette may end a path
  uint32_t threads = 0;         // 0: all hardware threads
  uint64_t seed = 1;
  bool pixelJitter = true;      // false: every sample through the pixel centre (as the rasterizer samples)
  bool emitterSampling = true;  // false: emissive surfaces found only by the bounces (unbiased, far noisier)
  glm::vec3 background{0.0f};   // radiance of rays that leave the scene

  static const OptionTable<PathTracerSettings>& table();  // spp, bounces, seed, pixel-jitter, emitter-sampling
};

struct PathTracerStats {
  double ms = 0.0;
  uint64_t samples = 0;          // camera samples (pixels x spp)
  double samplesPerSecond = 0.0;
};

// Called after each completed sample pass with (passes done, passes total).
using PathTracerProgress = std::function<void(uint32_t, uint32_t)>;

// Renders the snapshot's view. `bvh` must be synced to the world the snapshot was taken from.
render::ImageRgba pathTrace(const render::RenderSnapshot& snapshot, const EmbreeScene& bvh, const scene::AssetStore& assets,
                            uint32_t width, uint32_t height, const PathTracerSettings& settings,
                            PathTracerStats* stats = nullptr, const PathTracerProgress& progress = {});

}  // namespace dyngi::gi
