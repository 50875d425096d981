#include "techniques/temporal/vpl_paths.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "dyngi/engine/scene/light_units.h"
#include "bvh/scene_surfaces.h"
#include "sampling.h"
#include "shaders/shared/bounce_tail.h"
#include "indirect/emitters.h"

namespace dyngi::gi {
namespace {
constexpr float kPi = 3.14159265358979f;
using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

float uniform01(uint64_t& state) {
  state = mix64(state + 0x9E3779B97F4A7C15ULL);
  return float(state >> 40) * (1.0f / 16777216.0f);
}
float luminance(const glm::vec3& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

}  // namespace

VplPaths::VplPaths(const TemporalOptions& s) : settings_(s) {
  settings_.vpl.bounces = std::clamp(settings_.vpl.bounces, 1u, 3u);
  settings_.temporalSets = std::max(1u, settings_.temporalSets);
  settings_.vpl.vpls = settings_.vpl.effectiveVplCount();
  paths_ = settings_.vpl.vpls / settings_.vpl.bounces;
  const uint32_t n = settings_.vpl.vpls;
  reshootBudget_ = settings_.reshootBudget == 0 ? std::max(1u, n / settings_.temporalSets) : settings_.reshootBudget;
  vpls_.assign(n, PathVpl{});
  pathLight_.assign(paths_, LightState{});
  // Nothing rendered yet: every VPL counts as changed since its set was.
  changedSinceRendered_.assign(n, 2);
  setChanges_.assign(settings_.temporalSets, 0);
  setHardChanges_.assign(settings_.temporalSets, 0);
  for (uint32_t i = 0; i < n; ++i) ++setChanges_[setOf(i)], ++setHardChanges_[setOf(i)];
  reshootCounts_.assign(n, 0);
  uint64_t seedState = mix64(uint64_t(settings_.vpl.seed) * 0x9E3779B97F4A7C15ULL + 0x5EEDULL);
  sequenceOffset_ = {uniform01(seedState), uniform01(seedState), uniform01(seedState)};
  stats_.count = n;
  stats_.reshootBudget = reshootBudget_;
}

void VplPaths::update(const render::RenderSnapshot& snapshot, const EmbreeScene& bvh, const scene::AssetStore& assets,
                      const ecs::EntitySet& moved) {
  const EmitterSet emitters(snapshot, assets);  // once a frame: what invalidate() compares with, what replace() samples
  cacheEmitters(emitters);
  invalidate(snapshot, bvh, moved);
  replaceWith(snapshot, bvh, assets, emitters);
}

void VplPaths::cacheEmitters(const EmitterSet& emitters) {
  emitterSources_ = emitters.sources();
  emitterTotal_ = emitters.totalPower();
}

const EmitterSource* VplPaths::emitterSource(ecs::Entity entity) const {
  for (const EmitterSource& e : emitterSources_)
    if (e.entity == entity) return &e;
  return nullptr;
}

void VplPaths::refreshMaterials(const render::RenderSnapshot& snapshot, const EmbreeScene& bvh, const scene::AssetStore& assets,
                                const ecs::EntitySet& recoloured) {
  stats_.refreshedThisFrame = 0;
  if (recoloured.empty()) return;
  SceneSurfaces surfaces(snapshot, assets);
  const uint32_t B = settings_.vpl.bounces;
  for (uint32_t path = 0; path < paths_; ++path) {
    bool carry = false;  // an earlier bounce of this path changed its flux
    for (uint32_t b = 0; b < B; ++b) {
      const uint32_t i = path * B + b;
      PathVpl& v = vpls_[i];
      if (!v.valid) break;  // invalid: the rest of the path is reshot anyway
      // On an emissive source: its flux is the emission, which invalidate() compares; its albedo plays no part.
      if (b == 0 && pathLight_[path].type == kEmitterSource) continue;
      bool changed = false;
      if (carry) {
        // Cosine sampling: the parent's whole reflected flux travels along the ray.
        if (v.placed) v.incident = vpls_[i - 1].flux;
        changed = true;
      }
      if (v.placed && recoloured.count(v.surface)) {
        RayHit h = bvh.intersect(v.rayOrigin, v.rayDir, 0.0f, 1e30f);
        SurfaceHit sh;
        if (h.hit && h.entity == v.surface && surfaces.at(h, v.rayOrigin, v.rayDir, sh)) v.albedo = sh.diffuseAlbedo;
        changed = true;
      }
      if (v.placed && b + 1 == B && !v.probeSurface.isNull() && recoloured.count(v.probeSurface)) {
        // The tail's probe landed on the edited surface: the same probe ray, the new albedo.
        RayHit h = bvh.intersect(v.probeOrigin, v.probeDir, 0.0f, 1e30f);
        SurfaceHit sh;
        if (h.hit && surfaces.at(h, v.probeOrigin, v.probeDir, sh)) v.probeAlbedo = sh.diffuseAlbedo;
        changed = true;
      }
      if (!changed) continue;
      if (v.placed) v.flux = v.incident * v.albedo;
      carry = true;
      markChanged(i, /*hard=*/false);  // the same paths, re-weighted
      ++stats_.refreshedThisFrame;
    }
  }
}

void VplPaths::markChanged(uint32_t index, bool hard) {
  const uint8_t kind = hard ? 2 : 1, was = changedSinceRendered_[index];
  if (was >= kind) return;
  changedSinceRendered_[index] = kind;
  if (was == 0) ++setChanges_[setOf(index)];
  if (hard) ++setHardChanges_[setOf(index)];
}

void VplPaths::markSetRendered(uint32_t set) {
  for (uint32_t i = set; i < changedSinceRendered_.size(); i += settings_.temporalSets) changedSinceRendered_[i] = 0;
  setChanges_[set] = setHardChanges_[set] = 0;
}

float VplPaths::setStaleFraction(uint32_t set) const {
  const uint32_t n = uint32_t(vpls_.size()), T = settings_.temporalSets;
  const uint32_t inSet = set < n ? (n - set + T - 1) / T : 0;
  return inSet ? float(setHardChanges_[set]) / float(inSet) : 0.0f;
}

bool VplPaths::lightJumped(const LightState& from, glm::vec3 position, glm::vec3 direction, float scale) const {
  const float moveTolerance = std::max(settings_.lightMoveTolerance, 0.01f) * scale;
  const float turnTolerance = std::max(settings_.lightTurnTolerance, 0.01f);
  return glm::distance(position, from.position) > kLightJump * moveTolerance ||
         glm::dot(direction, from.direction) < std::cos(std::min(3.14159265f, kLightJump * turnTolerance));
}

void VplPaths::invalidateIndex(uint32_t index, bool hard) {
  uint32_t path = index / settings_.vpl.bounces;
  for (uint32_t b = index % settings_.vpl.bounces; b < settings_.vpl.bounces; ++b) {
    uint32_t i = path * settings_.vpl.bounces + b;
    if (!vpls_[i].valid) continue;
    vpls_[i].valid = false;
    if (hard) vpls_[i].seed = 0;  // its light changed: a new draw
    markChanged(i, hard);
    ++stats_.invalidatedThisFrame;
  }
}

void VplPaths::invalidate(const render::RenderSnapshot& snapshot, const EmbreeScene& bvh, const ecs::EntitySet& moved) {
  auto t0 = Clock::now();
  stats_.invalidatedThisFrame = 0;
  focus_ = cameraFocus(snapshot, settings_.vpl.directionalReach);
  FrameChecks checks{snapshot, bvh, moved};
  checks.scale = snapshot.sceneBounds.valid() ? std::max(glm::length(snapshot.sceneBounds.extent()), 1e-3f) : 1.0f;
  checks.eps = 1e-4f * checks.scale;
  checks.totalPower = emitterTotal_;
  for (const auto& l : snapshot.lights) checks.totalPower += lightPower(l, focus_.bounds);
  for (uint32_t i = 0; i < vpls_.size(); ++i) {
    if (!vpls_[i].valid) continue;
    if (pathLight_[i / settings_.vpl.bounces].type == kEmitterSource) checkEmitterPathVpl(i, checks);
    else checkLightPathVpl(i, checks);
  }
  stats_.invalidatedTotal += stats_.invalidatedThisFrame;
  uint32_t valid = 0;
  for (const auto& v : vpls_) valid += v.valid;
  stats_.valid = valid;
  stats_.invalidateMs = msSince(t0);
}

// The VPL's own ray, as shoot() traced it (the same origin, direction and start), must still reach it:
// in a scene that did not change this always agrees with the shot. A segment from the parent, its
// direction recomputed, can graze an edge the ray passed, and the VPL, traced again with its own
// stream, would come back where it was and be redrawn every frame.
bool VplPaths::rayStillReaches(const PathVpl& v, const FrameChecks& c) const {
  return !c.bvh.occluded(v.rayOrigin, v.rayDir, 0.0f, glm::dot(v.position - v.rayOrigin, v.rayDir) - c.eps);
}

// A ray that left the scene stays valid while nothing moved into it. Only a VPL's own ray counts: the
// later bounces of an escaped path have none (their parent decides).
bool VplPaths::escapedRayNowHits(uint32_t i, uint32_t b, const FrameChecks& c) const {
  if (c.moved.empty() || (b > 0 && !vpls_[i - 1].placed)) return false;
  const PathVpl& v = vpls_[i];
  return c.bvh.occluded(v.rayOrigin, v.rayDir, 0.0f, 1e30f);
}

// The bounce tail's probe (last bounce): the temporal technique gathers it where it landed, so it is
// stale when its surface moved, when something came between, or when something moved into the ray of
// one that left. Only a moved entity can do any of that.
bool VplPaths::probeStale(const PathVpl& v, uint32_t b, const FrameChecks& c) const {
  if (!settings_.vpl.bounceTail || b + 1 != settings_.vpl.bounces || !v.placed || c.moved.empty()) return false;
  const glm::vec3& o = v.probeOrigin;
  if (v.probeSurface.isNull()) return c.bvh.occluded(o, v.probeDir, 0.0f, 1e30f);
  return c.moved.count(v.probeSurface) > 0 || c.bvh.occluded(o, v.probeDir, 0.0f, glm::dot(v.probePosition - o, v.probeDir) - c.eps);
}

// A VPL of a path from an emissive surface: the surface must still emit what it did, with the same
// share of the power; then the VPL's own surface, ray and probe.
void VplPaths::checkEmitterPathVpl(uint32_t i, const FrameChecks& c) {
  const uint32_t path = i / settings_.vpl.bounces, b = i % settings_.vpl.bounces;
  const LightState& ls = pathLight_[path];
  const PathVpl& v = vpls_[i];
  const EmitterSource* source = emitterSource(ls.entity);
  const float share = source && c.totalPower > 0.0f ? source->power / c.totalPower : 0.0f;
  const bool emits = source && source->emissive == ls.radiant;
  if (!emits || std::abs(share - ls.probability) > kShareTolerance * ls.probability) {
    invalidateIndex(path * settings_.vpl.bounces, /*hard=*/true);
    if (!emits) pathLight_[path].entity = {};
    return;
  }
  if (!v.placed) {
    if (b > 0 && escapedRayNowHits(i, b, c)) invalidateIndex(i);
    return;
  }
  if (!v.surface.isNull() && c.moved.count(v.surface)) {  // the emitter itself (b = 0) or a surface after it
    invalidateIndex(i);
    return;
  }
  if (b == 0 ? probeStale(v, b, c) : !rayStillReaches(v, c) || probeStale(v, b, c)) invalidateIndex(i);  // on the emitter (b = 0): no ray to it
}

// A VPL of a path from a light: the light must be there, on, and where it was within the tolerances;
// then the VPL's own surface, the spot's cone, its ray and probe.
void VplPaths::checkLightPathVpl(uint32_t i, const FrameChecks& c) {
  const uint32_t path = i / settings_.vpl.bounces, b = i % settings_.vpl.bounces;
  const LightState& ls = pathLight_[path];
  const PathVpl& v = vpls_[i];
  const render::LightItem* light = nullptr;
  for (const auto& l : c.snapshot.lights)
    if (l.entity == ls.entity) light = &l;
  bool hard = true;  // gone or switched off
  if (!light || !light->light.enabled || !lightStillHolds(ls, *light, c, hard)) {
    invalidateIndex(path * settings_.vpl.bounces, hard);  // the whole path
    // Gone or off: the path's next shot, whatever light it finds, lights something new.
    if (!light || !light->light.enabled) pathLight_[path].entity = {};
    return;
  }
  if (!v.placed) {  // escaped ray: nothing to see, valid while its parent is and nothing moved into it
    if (escapedRayNowHits(i, b, c)) invalidateIndex(i);
    return;
  }
  if (!v.surface.isNull() && c.moved.count(v.surface)) {
    invalidateIndex(i);
    return;
  }
  // Still inside a spot's cone (it may have turned within the tolerance; a hair of slack for the cone's
  // own edge), and still reached by its ray: nothing came between it and its light or parent.
  if (b == 0 && light->light.type == scene::LightType::Spot &&
      glm::dot(glm::normalize(v.position - light->position), light->direction) < std::cos(light->light.outerConeAngle) - 1e-5f) {
    invalidateIndex(i);
    return;
  }
  if (!rayStillReaches(v, c) || probeStale(v, b, c)) invalidateIndex(i);
}

// Whether a path shot from `ls` still stands under `light` (on): power, cone and type exactly as they
// were, position and direction within the tolerances, and the light's share of the power as it was.
// `hard`: the light switched, was re-coloured or jumped, so what the path lit says little about now.
bool VplPaths::lightStillHolds(const LightState& ls, const render::LightItem& light, const FrameChecks& c, bool& hard) const {
  LightState now{light.entity, ls.position, ls.direction, light.light.color * light.light.intensity, light.light.range,
                 light.light.innerConeAngle, light.light.outerConeAngle, uint32_t(light.light.type), ls.probability};
  // Another light switched on or off, or changed its power: this light's share, which the path's flux
  // was divided by, is not what it was. Every path of every light is redrawn (hard: the mix changed).
  const float share = c.totalPower > 0.0f ? lightPower(light, focus_.bounds) / c.totalPower : 0.0f;
  const bool mixChanged = std::abs(share - ls.probability) > kShareTolerance * ls.probability;
  // A directional light's paths were shot over the focus of their frame: another focus, however near,
  // is another disc.
  const glm::vec3 position = shotFrom(light);
  const bool focusMoved = position != light.position && position != ls.position;  // shotFrom() gave the focus centre
  const bool lightMoved = focusMoved || (settings_.lightMoveTolerance > 0.0f ? glm::distance(position, ls.position) > settings_.lightMoveTolerance * c.scale
                                                                             : position != ls.position);
  const bool turned = settings_.lightTurnTolerance > 0.0f ? glm::dot(light.direction, ls.direction) < std::cos(settings_.lightTurnTolerance)
                                                          : light.direction != ls.direction;
  hard = !(now == ls) || mixChanged || lightJumped(ls, position, light.direction, c.scale);
  return now == ls && !lightMoved && !turned && !mixChanged;
}

glm::vec3 VplPaths::bounceTailScale() const {
  if (!settings_.vpl.bounceTail) return glm::vec3(1.0f);
  const uint32_t B = settings_.vpl.bounces;
  glm::dvec3 last(0.0), next(0.0);
  for (uint32_t i = B - 1; i < vpls_.size(); i += B) {
    const PathVpl& v = vpls_[i];
    if (!v.valid || !v.placed) continue;
    last += glm::dvec3(v.flux);
    next += glm::dvec3(v.flux * v.probeAlbedo);
  }
  return gpu::bounceTailScale(glm::vec3(last), glm::vec3(next));
}

void VplPaths::shootProbe(PathVpl& v, uint64_t& rng, float scale, const EmbreeScene& bvh, const SceneSurfaces& surfaces) const {
  float u1 = uniform01(rng), u2 = uniform01(rng);
  v.probeDir = cosineDirection(v.normal, u1, u2);
  v.probeAlbedo = glm::vec3(0.0f);
  v.probeSurface = {};
  const glm::vec3 o = v.probeOrigin = v.position + v.normal * (1e-4f * scale);
  RayHit h = bvh.intersect(o, v.probeDir, 0.0f, 1e30f);
  SurfaceHit sh;
  if (h.hit && surfaces.at(h, o, v.probeDir, sh)) {
    v.probeAlbedo = sh.diffuseAlbedo;
    v.probePosition = sh.position;
    v.probeNormal = sh.shadingNormal;
    v.probeSurface = sh.entity;
  }
}

bool VplPaths::shoot(uint32_t index, const render::RenderSnapshot& snapshot, const EmbreeScene& bvh, const SceneSurfaces& surfaces,
                     const EmitterSet& emitters) {
  const uint32_t path = index / settings_.vpl.bounces, b = index % settings_.vpl.bounces;
  // Traced again with its own stream, unless it has none (PathVpl::seed).
  uint64_t seed = vpls_[index].seed;
  if (seed == 0) seed = mix64(settings_.vpl.seed * 0x51ED27ULL + (++shotCounter_) * 0x2545F4914F6CDD1DULL + index);
  uint64_t rng = seed;
  const float scale = surfaces.sceneScale();
  PathRay ray;
  if (b == 0) {
    // A path's light pick and first direction come from the R3 sequence, not from rng: independent
    // random paths clump and leave gaps, and a face lit by the few VPLs near it then comes out tens of
    // percent off with one seed and the other way with the next. The paths with the same path % T share
    // a temporal set and take a consecutive run of the sequence, so a set alone is evenly spread and all
    // sets together are too. The point belongs to the path: redrawn for any reason, it keeps it.
    const uint32_t T = settings_.temporalSets, runLength = (paths_ + T - 1) / T;
    const glm::vec3 seq = r3Point(uint64_t(path % T) * runLength + path / T, sequenceOffset_);
    float lightsTotal = 0.0f;
    for (const auto& l : snapshot.lights) lightsTotal += lightPower(l, focus_.bounds);
    const float total = lightsTotal + emitters.totalPower();
    if (total <= 0.0f) return false;
    const float u = seq.x * total;
    if (u >= lightsTotal) {  // the emissive surfaces, in proportion to their power
      vpls_[index] = vplOnEmitter(path, seq, u, lightsTotal, total, rng, bvh, surfaces, emitters);
      vpls_[index].seed = seed;
      return true;
    }
    ray = rayFromLight(path, seq, u, total, snapshot);
  } else {
    const PathVpl& parent = vpls_[index - 1];
    if (!parent.valid) return false;
    if (!parent.placed || luminance(parent.flux) <= 0.0f) {  // nothing to carry on
      PathVpl child;
      child.valid = true;
      child.seed = seed;
      vpls_[index] = child;
      return true;
    }
    // Random, not the sequence: consecutive pool indices are M apart in it, so a child's point would be its
    // parent's shifted by a constant, every path bending the same way at each bounce.
    const float u1 = uniform01(rng), u2 = uniform01(rng);
    ray.dir = cosineDirection(parent.normal, u1, u2);
    ray.origin = parent.position + parent.normal * (1e-4f * scale);
    ray.throughput = parent.flux;  // cosine sampling: the parent's whole reflected flux travels along the ray
  }
  vpls_[index] = landRay(ray, path, b, rng, scale, snapshot, bvh, surfaces);
  vpls_[index].seed = seed;
  return true;
}

// A path that starts on an emissive surface (indirect/emitters.h): the VPL on it is its bounce 0.
PathVpl VplPaths::vplOnEmitter(uint32_t path, glm::vec3 seq, float u, float lightsTotal, float total, uint64_t& rng,
                               const EmbreeScene& bvh, const SceneSurfaces& surfaces, const EmitterSet& emitters) {
  const float pEmitters = emitters.totalPower() / total;
  const float pick = std::clamp((u - lightsTotal) / emitters.totalPower(), 0.0f, 0.99999994f);  // still stratified
  const EmitterSample e = emitters.sample(pick, seq.y, seq.z, uniform01(rng));
  PathVpl v;
  v.valid = true;
  if (!e.entity.isNull()) {
    v.placed = true;
    v.position = e.position;
    v.normal = e.normal;
    v.flux = v.incident = e.flux / (pEmitters * float(paths_));
    v.albedo = glm::vec3(1.0f);
    v.surface = e.entity;
    if (settings_.vpl.bounceTail && settings_.vpl.bounces == 1) shootProbe(v, rng, surfaces.sceneScale(), bvh, surfaces);
  }
  glm::vec3 emissive(0.0f);
  float power = 0.0f;
  for (const EmitterSource& src : emitters.sources())
    if (src.entity == e.entity) emissive = src.emissive, power = src.power;
  pathLight_[path] = LightState{e.entity, {}, {}, emissive, 0, 0, 0, kEmitterSource, power / total};
  return v;
}

// A path that starts at a light, picked in proportion to its power (u in [0, the lights' total)): its
// first ray from the light (directional: from a disc over the scene), carrying the light's flux over
// the chance it was picked and the paths that share it.
VplPaths::PathRay VplPaths::rayFromLight(uint32_t path, glm::vec3 seq, float u, float total, const render::RenderSnapshot& snapshot) {
  const render::LightItem* light = nullptr;
  float acc = 0.0f;
  for (const auto& l : snapshot.lights) {
    float p = lightPower(l, focus_.bounds);
    if (p <= 0.0f) continue;
    light = &l;
    acc += p;
    if (u < acc) break;
  }
  const float pLight = lightPower(*light, focus_.bounds) / total;
  const scene::Light& L = light->light;
  const glm::vec3 radiant = L.color * L.intensity;
  const float u1 = seq.y, u2 = seq.z;
  PathRay ray;
  if (L.type == scene::LightType::Directional) {
    // A disc across the light over the focus (camera_focus.h), its rays starting outside the scene.
    float r = 0.5f * glm::length(focus_.bounds.extent()) + 1e-3f;
    const scene::Aabb& scene = snapshot.sceneBounds;
    const float back = focus_.wholeScene ? 2.0f * r : 2.0f * (0.5f * glm::length(scene.extent()) + glm::distance(focus_.centre, scene.center()));
    glm::vec3 b1, b2;
    orthonormalBasis(light->direction, b1, b2);
    float rr = r * std::sqrt(u1), phi = 2.0f * kPi * u2;
    ray.origin = focus_.bounds.center() - light->direction * back + rr * (std::cos(phi) * b1 + std::sin(phi) * b2);
    ray.dir = light->direction;
    ray.throughput = radiant * (kPi * r * r) / pLight;  // E x disc area / p(light)
  } else if (L.type == scene::LightType::Spot) {
    ray.origin = light->position;
    float cosOuter = std::cos(std::clamp(L.outerConeAngle, 1e-3f, 1.5707f));
    float ct = 1.0f - u1 * (1.0f - cosOuter), st = std::sqrt(std::max(0.0f, 1.0f - ct * ct));
    glm::vec3 b1, b2;
    orthonormalBasis(light->direction, b1, b2);
    ray.dir = glm::normalize(st * std::cos(2.0f * kPi * u2) * b1 + st * std::sin(2.0f * kPi * u2) * b2 + ct * light->direction);
    const float pdf = 1.0f / (2.0f * kPi * (1.0f - cosOuter));
    ray.throughput = radiant * scene::spotFalloff(ct, L.innerConeAngle, L.outerConeAngle) / (pdf * pLight);
  } else {
    ray.origin = light->position;
    float z = 1.0f - 2.0f * u1, s = std::sqrt(std::max(0.0f, 1.0f - z * z));
    ray.dir = {s * std::cos(2.0f * kPi * u2), s * std::sin(2.0f * kPi * u2), z};
    const float pdf = 1.0f / (4.0f * kPi);
    ray.throughput = radiant / (pdf * pLight);
  }
  pathLight_[path] = LightState{light->entity, shotFrom(*light), light->direction, radiant, L.range, L.innerConeAngle, L.outerConeAngle,
                                uint32_t(L.type), pLight};
  ray.throughput /= float(paths_);
  return ray;
}

// The VPL where `ray` lands (bounce b of its path), or an unplaced one when it leaves the scene.
PathVpl VplPaths::landRay(const PathRay& ray, uint32_t path, uint32_t b, uint64_t& rng, float scale, const render::RenderSnapshot& snapshot,
                          const EmbreeScene& bvh, const SceneSurfaces& surfaces) const {
  PathVpl v;
  v.valid = true;
  v.rayOrigin = ray.origin;
  v.rayDir = ray.dir;
  RayHit h = bvh.intersect(ray.origin, ray.dir, 0.0f, 1e30f);
  SurfaceHit sh;
  if (!h.hit || !surfaces.at(h, ray.origin, ray.dir, sh)) return v;
  glm::vec3 throughput = ray.throughput;
  if (b == 0) {
    const render::LightItem* light = nullptr;
    for (const auto& l : snapshot.lights)
      if (l.entity == pathLight_[path].entity) light = &l;
    if (light && light->light.type != scene::LightType::Directional) throughput *= scene::rangeWindow(h.t, light->light.range);
  }
  v.placed = true;
  v.position = sh.position;
  v.normal = sh.shadingNormal;
  v.incident = throughput;
  v.albedo = sh.diffuseAlbedo;
  v.flux = throughput * sh.diffuseAlbedo;
  v.surface = sh.entity;
  if (settings_.vpl.bounceTail && b + 1 == settings_.vpl.bounces) shootProbe(v, rng, scale, bvh, surfaces);
  return v;
}

void VplPaths::replace(const render::RenderSnapshot& snapshot, const EmbreeScene& bvh, const scene::AssetStore& assets) {
  const EmitterSet emitters(snapshot, assets);
  cacheEmitters(emitters);
  replaceWith(snapshot, bvh, assets, emitters);
}

void VplPaths::replaceWith(const render::RenderSnapshot& snapshot, const EmbreeScene& bvh, const scene::AssetStore& assets,
                           const EmitterSet& emitters) {
  auto t0 = Clock::now();
  focus_ = cameraFocus(snapshot, settings_.vpl.directionalReach);
  stats_.replacedThisFrame = 0;
  const uint32_t n = uint32_t(vpls_.size());
  uint32_t budget = reshootBudget_;
  if (settings_.reshootBurst > budget) {
    // More invalid than the budget (a light switched, moved or turned): reshoot them all now, up to the
    // burst limit, so the pool is whole again this frame instead of T frames later.
    uint32_t invalid = 0;
    for (const PathVpl& v : vpls_) invalid += !v.valid;
    budget = std::max(budget, std::min(invalid, settings_.reshootBurst));
  }
  SceneSurfaces surfaces(snapshot, assets);
  for (uint32_t visited = 0; visited < n && budget > 0; ++visited) {
    uint32_t i = cursor_;
    cursor_ = (cursor_ + 1) % n;
    if (vpls_[i].valid) continue;
    // A VPL is reshot only from a valid parent: start at the first invalid VPL of its path.
    uint32_t first = i;
    while (first % settings_.vpl.bounces > 0 && !vpls_[first - 1].valid) --first;
    // A path shot for the first time, or after its light went off or away, brings light its set did not
    // have (a hard change; TemporalOptions::dropStaleSets); its later bounces follow. Switches, power
    // changes and jumps of a light that stays were marked when invalidate() found them.
    bool hard = false;
    for (uint32_t j = first; j <= i && budget > 0; ++j) {
      const uint32_t path = j / settings_.vpl.bounces;
      const bool hadNoLight = pathLight_[path].entity.isNull();
      if (!shoot(j, snapshot, bvh, surfaces, emitters)) break;
      if (j % settings_.vpl.bounces == 0) hard = hadNoLight;
      --budget;
      ++stats_.replacedThisFrame;
      ++reshootCounts_[j];
      markChanged(j, hard);
    }
  }
  stats_.replacedTotal += stats_.replacedThisFrame;
  uint32_t valid = 0;
  for (const auto& v : vpls_) valid += v.valid;
  stats_.valid = valid;
  stats_.replaceMs = msSince(t0);
}

}  // namespace dyngi::gi
