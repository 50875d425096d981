#pragma once
// Incremental instant radiosity on the CPU: VPLs stored as light paths and kept valid incrementally.
//
// The pool is an array: index = path * bounces + bounce. The VPL of path p at bounce b has as parent
// the light (b = 0) or the VPL (p, b - 1). Each frame:
//  1. invalidation: a VPL is invalid when its parent no longer sees it (Embree occlusion), when the
//     entity its surface belongs to moved, deformed or changed its material, when its light moved/turned/changed or is gone,
//     when its light's share of the total power changed (another light switched on or off),
//     or when it left its spot light's cone; invalidating a VPL invalidates its children;
//  2. replacement: at most `reshootBudget` VPLs are reshot (all invalid ones, up to `reshootBurst`, when
//     more are invalid: a light switched or moved), found by a round-robin cursor that goes on where the
//     last frame stopped; a VPL is reshot only when its parent is valid. A path starts from a light or
//     an emissive surface, in proportion to their power (an emissive surface's bounce-0 VPL lies on it,
//     vpl/emitters.h). Light rays sample the light's emission (a spot's cone, a point's sphere, a directional light's beam over the scene),
//     VPL rays a cosine hemisphere; the closest hit comes from Embree and the flux from the hit's
//     material (texture via barycentrics). A ray that leaves the scene makes a valid VPL with no flux
//     (the estimator's zero), so reshooting always completes.
//  3. temporal sets: set k holds VPLs[T i + k]; sets whose VPLs changed since they were last rendered
//     are reported dirty.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "dyngi/engine/ecs/entity_map.h"
#include "dyngi/engine/render/snapshot.h"
#include "dyngi/gi/bvh.h"
#include "dyngi/gi/temporal_options.h"
#include "camera_focus.h"

namespace dyngi::gi {

struct PathVpl {
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f, 1.0f, 0.0f};
  glm::vec3 flux{0.0f};          // reflected flux (W); zero for a path that left the scene
  ecs::Entity surface{};         // entity the VPL lies on (null when the path left the scene)
  bool valid = false;
  bool placed = false;           // has a position (false: escaped ray, zero flux)
  // How it was placed, so that a material edit re-evaluates the same path instead of drawing a new one:
  // the ray that found it, the flux that arrived along it, and the surface's diffuse albedo there
  // (flux = incident * albedo).
  glm::vec3 rayOrigin{0.0f}, rayDir{0.0f, 0.0f, 1.0f};
  glm::vec3 incident{0.0f};
  glm::vec3 albedo{0.0f};
  // Last bounce only (VplOptions::bounceTail): one more cosine ray from it. Its landing surface's
  // diffuse albedo (0 when it leaves the scene) measures how much flux a further bounce keeps
  // (bounceTailScale); where it lands (probeSurface not null) the temporal technique gathers it as a VPL
  // of the next bounce with flux x probeAlbedo x that scale (TemporalIndirect::prepare).
  glm::vec3 probeOrigin{0.0f}, probeDir{0.0f, 1.0f, 0.0f};  // the ray as shot (the scene's scale sets its lift)
  glm::vec3 probeAlbedo{0.0f};
  glm::vec3 probePosition{0.0f}, probeNormal{0.0f, 1.0f, 0.0f};
  ecs::Entity probeSurface{};
  // The random stream it was shot with. Invalidated by a change of geometry (an occluder, a moved
  // surface, a cut) it is traced again with the same stream, so the pool stays the one a fresh shot
  // draws in the scene as it is now: a new stream would leave the changed region with only its share of
  // the reshot paths. A change of its light (hard) draws a new one. 0: none yet.
  uint64_t seed = 0;
};

// One emissive entity a path can start from (gi_module/vpl/emitters.h lists them): its power
// (luminance, both sides) and the emission factor it was drawn with.
struct EmitterSource {
  ecs::Entity entity{};
  float power = 0.0f;
  glm::vec3 emissive{0.0f};
};

struct VplPathStats {
  uint32_t count = 0, valid = 0;
  uint32_t invalidatedThisFrame = 0, replacedThisFrame = 0;
  uint32_t refreshedThisFrame = 0;  // VPLs whose flux a material edit re-evaluated (the paths kept)
  uint64_t invalidatedTotal = 0, replacedTotal = 0;
  uint32_t reshootBudget = 0;
  double invalidateMs = 0, replaceMs = 0;
};

class VplPaths {
 public:
  // Uses the options' VPL count rounded to a multiple of the bounces, bounces clamped to 1..3 and T >= 1;
  // settings() reports those values.
  explicit VplPaths(const TemporalOptions& settings = {});

  // One frame: invalidate against `moved` (entities whose world transform or mesh changed) and the
  // snapshot's lights, then replace up to the budget.
  void update(const render::RenderSnapshot& snapshot, const EmbreeScene& bvh, const scene::AssetStore& assets,
              const ecs::EntitySet& moved);
  void invalidate(const render::RenderSnapshot& snapshot, const EmbreeScene& bvh, const ecs::EntitySet& moved);
  // A material edit changes what a surface reflects, not where paths go: each valid VPL on a re-coloured
  // entity gets its albedo again (its ray re-traced to the same hit), and its flux and every later
  // bounce's flux follow. Reshooting them instead would draw new directions, and the edited surface
  // would keep only the share of them that lands on it again: a bias. Entities that also moved or
  // deformed are left to invalidate().
  void refreshMaterials(const render::RenderSnapshot& snapshot, const EmbreeScene& bvh, const scene::AssetStore& assets,
                        const ecs::EntitySet& recoloured);
  void replace(const render::RenderSnapshot& snapshot, const EmbreeScene& bvh, const scene::AssetStore& assets);

  const std::vector<PathVpl>& vpls() const { return vpls_; }
  // What the probes' flux (the next bounce's) is multiplied by so that it carries every later bounce too
  // (shaders/shared/bounce_tail.h), from the valid last-bounce VPLs' probes; 1 with bounceTail off.
  glm::vec3 bounceTailScale() const;
  const TemporalOptions& settings() const { return settings_; }
  const VplPathStats& stats() const { return stats_; }
  const CameraFocus& focus() const { return focus_; }  // this frame's, for directional lights
  uint32_t paths() const { return paths_; }
  uint32_t bounces() const { return settings_.vpl.bounces; }
  uint32_t setOf(uint32_t index) const { return index % settings_.temporalSets; }
  // Sets with a VPL invalidated, replaced or re-coloured since markSetRendered(set).
  bool setDirty(uint32_t set) const { return setChanges_[set] != 0; }
  // The fraction of the set's VPLs that changed hard since then: their light was switched on or off,
  // re-coloured, or jumped (moved or turned kLightJump times its tolerance), so the set's stored light
  // says little about them now. Soft changes (a light moving by its tolerance, an occluder, a moved
  // surface) keep the stored light a fair estimate until the set is gathered again.
  float setStaleFraction(uint32_t set) const;
  void markSetRendered(uint32_t set);
  static constexpr float kLightJump = 5.0f;
  // A light's share of the total power may drift this much (relative) before its paths are redrawn.
  static constexpr float kShareTolerance = 0.01f;
  uint32_t cursor() const { return cursor_; }
  // How many times each VPL has been reshot (fairness checks).
  const std::vector<uint32_t>& reshootCounts() const { return reshootCounts_; }

 private:
  struct LightState {
    ecs::Entity entity{};
    glm::vec3 position{0.0f}, direction{0.0f};
    glm::vec3 radiant{0.0f};
    float range = 0, inner = 0, outer = 0;
    uint32_t type = 0;
    float probability = 0;  // the chance this light had of being picked (its share of the lights' power)
    bool operator==(const LightState&) const = default;
  };
  // Paths whose source is an emissive surface (vpl/emitters.h) rather than a light: LightState::type.
  static constexpr uint32_t kEmitterSource = 3;
  // The emissive surface a path started from, as the last EmitterSet listed it (null: it emits no more).
  const EmitterSource* emitterSource(ecs::Entity entity) const;
  void cacheEmitters(const class EmitterSet& emitters);
  void replaceWith(const render::RenderSnapshot& snapshot, const EmbreeScene& bvh, const scene::AssetStore& assets,
                   const class EmitterSet& emitters);
  void invalidateIndex(uint32_t index, bool hard = false);
  // What invalidate() checks each VPL against this frame.
  struct FrameChecks {
    const render::RenderSnapshot& snapshot;
    const EmbreeScene& bvh;
    const ecs::EntitySet& moved;
    float scale = 1.0f, eps = 0.0f, totalPower = 0.0f;  // the scene's diagonal, a ray's slack, lights' and emitters' power
  };
  bool rayStillReaches(const PathVpl& v, const FrameChecks& c) const;
  bool escapedRayNowHits(uint32_t i, uint32_t b, const FrameChecks& c) const;
  bool probeStale(const PathVpl& v, uint32_t b, const FrameChecks& c) const;
  void checkEmitterPathVpl(uint32_t i, const FrameChecks& c);
  void checkLightPathVpl(uint32_t i, const FrameChecks& c);
  bool lightStillHolds(const LightState& ls, const render::LightItem& light, const FrameChecks& c, bool& hard) const;
  void markChanged(uint32_t index, bool hard);  // counts a VPL once per set rendering (and once more if hard)
  bool lightJumped(const LightState& from, glm::vec3 position, glm::vec3 direction, float scale) const;
  void shootProbe(PathVpl& v, uint64_t& rng, float scale, const EmbreeScene& bvh, const class SceneSurfaces& surfaces) const;
  bool shoot(uint32_t index, const render::RenderSnapshot& snapshot, const EmbreeScene& bvh, const class SceneSurfaces& surfaces,
             const class EmitterSet& emitters);
  struct PathRay {
    glm::vec3 origin{0.0f}, dir{0.0f}, throughput{0.0f};  // throughput: the flux the ray carries
  };
  PathVpl vplOnEmitter(uint32_t path, glm::vec3 seq, float u, float lightsTotal, float total, uint64_t& rng, const EmbreeScene& bvh,
                       const class SceneSurfaces& surfaces, const class EmitterSet& emitters);
  PathRay rayFromLight(uint32_t path, glm::vec3 seq, float u, float total, const render::RenderSnapshot& snapshot);
  PathVpl landRay(const PathRay& ray, uint32_t path, uint32_t b, uint64_t& rng, float scale, const render::RenderSnapshot& snapshot,
                  const EmbreeScene& bvh, const class SceneSurfaces& surfaces) const;

  TemporalOptions settings_;
  uint32_t reshootBudget_ = 0;  // per frame, as used (settings_.reshootBudget, or one set's worth for 0)
  uint32_t paths_ = 0;
  // Where this frame's directional light paths are shot over (invalidate, replace); a path records the
  // focus centre as its light's position (shotFrom), so a focus that moved a step reshoots them.
  CameraFocus focus_;
  glm::vec3 shotFrom(const render::LightItem& light) const {
    return light.light.type == scene::LightType::Directional && !focus_.wholeScene ? focus_.centre : light.position;
  }
  glm::vec3 sequenceOffset_{0.0f};  // the seed's rotation of the R3 sequence the VPLs are drawn from (shoot)
  std::vector<PathVpl> vpls_;
  std::vector<LightState> pathLight_;   // per path: the light state its bounce-0 VPL was shot from
  // The emissive surfaces' power at the last update() (what invalidate() compares paths against).
  std::vector<EmitterSource> emitterSources_;
  float emitterTotal_ = 0.0f;
  std::vector<uint8_t> changedSinceRendered_;  // per VPL: 0 no, 1 soft, 2 hard change since its set was rendered
  std::vector<uint32_t> setChanges_;           // per set: its VPLs changed since it was rendered
  std::vector<uint32_t> setHardChanges_;       // ... of which hard
  std::vector<uint32_t> reshootCounts_;
  uint32_t cursor_ = 0;
  uint64_t shotCounter_ = 0;
  VplPathStats stats_;
};

}  // namespace dyngi::gi
