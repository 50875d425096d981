#pragma once
// Emissive surfaces as VPL sources (both VPL techniques): every triangle of a draw whose material emits,
// sampled in proportion to its power. An emitter sample is a VPL on the emitter itself: a Lambertian
// emitter is a cosine-distributed source, exactly what a VPL is, so gathering it gives the emitter's
// light on the scene (the path tracer's first bounce off an emissive hit) and its children the bounces
// after. Emitters are two-sided, as the path tracer and the rasterizer treat them: a sample emits from a
// side picked at random.
#include <optional>
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>

#include "dyngi/engine/render/snapshot.h"
#include "bvh/scene_surfaces.h"
#include "techniques/temporal/vpl_paths.h"  // EmitterSource

namespace dyngi::gi {

struct EmitterSample {
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f, 1.0f, 0.0f};  // the side it emits from
  glm::vec3 faceNormal{0.0f, 1.0f, 0.0f};  // the triangle's, on that side (what area and solid angle convert by)
  glm::vec3 flux{0.0f};                // Le(x) 2 pi A / p(triangle): one sample's estimate of all emitters' flux
  glm::vec3 radiance{0.0f};            // Le(x), textured
  float pdfArea = 0.0f;                // density of this point per unit area: p(triangle) / A; 0: no sample
  ecs::Entity entity{};
};

class EmitterSet {
 public:
  EmitterSet(const render::RenderSnapshot& snapshot, const scene::AssetStore& assets);
  bool empty() const { return triangles_.empty(); }
  // Emitted power (luminance of the flux, both sides), what competes with the lights' power for paths.
  float totalPower() const { return total_; }
  float power(ecs::Entity entity) const;  // one entity's share of totalPower (0: it does not emit)
  const std::vector<EmitterSource>& sources() const { return sources_; }
  // u0 picks the triangle, u1 u2 the point, u3 the side.
  EmitterSample sample(float u0, float u1, float u2, float u3) const;
  // The density per unit area with which sample() picks a point of this triangle (0: never), for
  // weighting a surface hit against emitter sampling (the path tracer's MIS).
  float pdfArea(ecs::Entity entity, uint32_t primitive) const;

 private:
  struct Triangle {
    size_t draw;
    uint32_t primitive;
    float area;
    float cdf;  // cumulative power up to and including this triangle
  };
  const render::RenderSnapshot& snap_;
  const scene::AssetStore& assets_;
  std::optional<SceneSurfaces> surfaces_;  // made only when something emits (it maps every draw)
  std::vector<Triangle> triangles_;
  std::vector<EmitterSource> sources_;
  std::unordered_map<ecs::Entity, std::vector<float>> pdfArea_;  // per emitting draw, per primitive
  float total_ = 0.0f;
};

// Radiant power of a light (luminance): what a light's share of the VPL paths is drawn by, against the
// emitters' totalPower(). Point: 4 pi I, spot: I x its cone's solid angle, directional: E over the disc
// that covers the scene; 0 when switched off.
float lightPower(const render::LightItem& light, const scene::Aabb& sceneBounds);

// Luminance of a linear RGB value (Rec. 709), the one weight every power comparison uses.
inline float emitterLuminance(const glm::vec3& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

}  // namespace dyngi::gi
