#include "dyngi/engine/scene/animation.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/quaternion.hpp>
#include <unordered_set>

namespace dyngi::scene {

int Animator::findClip(const std::string& clipName) const {
  for (size_t i = 0; i < clips.size(); ++i)
    if (clips[i].name == clipName) return int(i);
  return -1;
}

namespace {
glm::vec4 slerpVec(const glm::vec4& a, const glm::vec4& b, float u) {
  glm::quat qa(a.w, a.x, a.y, a.z), qb(b.w, b.x, b.y, b.z);
  glm::quat q = glm::slerp(qa, qb, u);  // takes the short way
  return {q.x, q.y, q.z, q.w};
}
}  // namespace

glm::vec4 sampleChannel(const AnimationChannel& c, float t) {
  const size_t n = c.times.size();
  if (n == 0) return glm::vec4(0.0f);
  const bool cubic = c.interpolation == Interpolation::CubicSpline;
  auto value = [&](size_t k) { return cubic ? c.values[k * 3 + 1] : c.values[k]; };
  auto normalizeIfRotation = [&](glm::vec4 v) {
    if (c.path != AnimationPath::Rotation) return v;
    float len = glm::length(v);
    return len > 0.0f ? v / len : glm::vec4(0, 0, 0, 1);
  };
  if (t <= c.times.front() || n == 1) return normalizeIfRotation(value(0));
  if (t >= c.times.back()) return normalizeIfRotation(value(n - 1));
  size_t k = size_t(std::upper_bound(c.times.begin(), c.times.end(), t) - c.times.begin()) - 1;
  float t0 = c.times[k], t1 = c.times[k + 1], dt = t1 - t0;
  float u = dt > 0.0f ? (t - t0) / dt : 0.0f;
  switch (c.interpolation) {
    case Interpolation::Step: return normalizeIfRotation(value(k));
    case Interpolation::Linear:
      if (c.path == AnimationPath::Rotation) return normalizeIfRotation(slerpVec(value(k), value(k + 1), u));
      return glm::mix(value(k), value(k + 1), u);
    case Interpolation::CubicSpline: {
      // Hermite spline with tangents scaled by the key interval (glTF 2.0, appendix C).
      glm::vec4 p0 = c.values[k * 3 + 1], m0 = c.values[k * 3 + 2] * dt;
      glm::vec4 p1 = c.values[(k + 1) * 3 + 1], m1 = c.values[(k + 1) * 3] * dt;
      float u2 = u * u, u3 = u2 * u;
      glm::vec4 v = (2 * u3 - 3 * u2 + 1) * p0 + (u3 - 2 * u2 + u) * m0 + (-2 * u3 + 3 * u2) * p1 + (u3 - u2) * m1;
      return normalizeIfRotation(v);
    }
  }
  return value(k);
}

void AnimationSystem::run(ecs::World& world, const ecs::SystemContext& ctx) {
  std::vector<Entity> animators;
  world.each<Animator>([&](Entity e, const Animator&) { animators.push_back(e); });
  for (Entity e : animators) {
    Animator& a = world.write<Animator>(e);
    if (!a.playing || a.active < 0 || size_t(a.active) >= a.clips.size()) continue;
    const AnimationClip& clip = a.clips[size_t(a.active)];
    a.time += float(ctx.time.dt) * a.speed;
    if (clip.duration > 0.0f) a.time = a.loop ? std::fmod(std::fmod(a.time, clip.duration) + clip.duration, clip.duration)
                                              : std::clamp(a.time, 0.0f, clip.duration);
    for (const AnimationChannel& ch : clip.channels) {
      if (ch.node >= a.nodes.size() || !world.alive(a.nodes[ch.node]) || !world.has<Transform>(a.nodes[ch.node])) continue;
      Entity target = a.nodes[ch.node];
      glm::vec4 v = sampleChannel(ch, a.time);
      const Transform& cur = world.get<Transform>(target);
      switch (ch.path) {
        case AnimationPath::Translation:
          if (cur.translation != glm::vec3(v)) world.write<Transform>(target).translation = glm::vec3(v);
          break;
        case AnimationPath::Scale:
          if (cur.scale != glm::vec3(v)) world.write<Transform>(target).scale = glm::vec3(v);
          break;
        case AnimationPath::Rotation: {
          glm::quat q(v.w, v.x, v.y, v.z);
          if (cur.rotation != q) world.write<Transform>(target).rotation = q;
          break;
        }
      }
    }
  }
}

void skinMesh(const MeshData& bind, const std::vector<glm::mat4>& jointMatrices, MeshData& out) {
  const size_t n = bind.positions.size();
  out.positions.resize(n);
  out.normals.resize(n);
  const bool tangents = bind.tangents.size() == n;  // a normal-textured mesh: its frame turns with it
  out.tangents.resize(tangents ? n : 0);
  for (size_t i = 0; i < n; ++i) {
    glm::mat4 m(0.0f);
    float wsum = 0.0f;
    for (int k = 0; k < 4; ++k) {
      float w = bind.weights[i][k];
      uint32_t j = bind.joints[i][k];
      if (w <= 0.0f || j >= jointMatrices.size()) continue;
      m += w * jointMatrices[j];
      wsum += w;
    }
    if (wsum <= 0.0f) m = glm::mat4(1.0f);
    else if (std::abs(wsum - 1.0f) > 1e-3f) m /= wsum;  // renormalise sloppy weights
    out.positions[i] = glm::vec3(m * glm::vec4(bind.positions[i], 1.0f));
    glm::vec3 nrm = glm::mat3(m) * (i < bind.normals.size() ? bind.normals[i] : glm::vec3(0, 1, 0));
    float len = glm::length(nrm);
    out.normals[i] = len > 0.0f ? nrm / len : glm::vec3(0, 1, 0);
    if (tangents) {
      const glm::vec3 t = glm::mat3(m) * glm::vec3(bind.tangents[i]);
      const float tl = glm::length(t);
      out.tangents[i] = glm::vec4(tl > 0.0f ? t / tl : glm::vec3(1, 0, 0), bind.tangents[i].w);
    }
  }
  out.computeBounds();
}

void SkinningSystem::run(ecs::World& world, const ecs::SystemContext& ctx) {
  skinnedLastRun_ = 0;
  std::unordered_set<Entity> moved;
  world.forEachChanged<WorldTransform>(ctx.lastRun, [&](Entity e) { moved.insert(e); });
  bool firstRun = ctx.lastRun == 0;
  std::vector<Entity> skinned;
  world.each<SkinnedMesh, WorldTransform>([&](Entity e, const SkinnedMesh&, const WorldTransform&) { skinned.push_back(e); });
  for (Entity e : skinned) {
    const SkinnedMesh& s = world.get<SkinnedMesh>(e);
    bool dirty = firstRun || moved.count(e);
    for (size_t j = 0; j < s.joints.size() && !dirty; ++j) dirty = moved.count(s.joints[j]) > 0;
    if (!dirty) continue;
    glm::mat4 invMesh = glm::inverse(world.get<WorldTransform>(e).matrix);
    std::vector<glm::mat4> jm(s.joints.size(), glm::mat4(1.0f));
    for (size_t j = 0; j < s.joints.size(); ++j) {
      const WorldTransform* jw = world.alive(s.joints[j]) ? world.tryGet<WorldTransform>(s.joints[j]) : nullptr;
      glm::mat4 ibm = j < s.inverseBind.size() ? s.inverseBind[j] : glm::mat4(1.0f);
      if (jw) jm[j] = invMesh * jw->matrix * ibm;
    }
    skinMesh(assets_.mesh(s.bindPose), jm, assets_.meshForWrite(s.deformed));
    ++skinnedLastRun_;
  }
}

}  // namespace dyngi::scene
