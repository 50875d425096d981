#include "techniques/vct/vct_cpu.h"

#include "techniques/vct/shaders/vct_shared.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace dyngi::gi {

namespace {
constexpr uint32_t kSlabs = DYNGI_VCT_SLABS;
constexpr int kMaxSteps = DYNGI_VCT_MAX_STEPS;
constexpr float kSurfaceClearance = float(DYNGI_VCT_SURFACE_CLEARANCE);
glm::vec4 over(const glm::vec4& front, const glm::vec4& back) { return front + (1.0f - front.a) * back; }

// A w x h x d level with each texel from texel(x, y, z).
template <class Texel>
VolumeLevel makeLevel(uint32_t w, uint32_t h, uint32_t d, Texel texel) {
  VolumeLevel out{w, h, d, {}};
  out.texels.resize(size_t(w) * h * d);
  for (uint32_t z = 0; z < d; ++z)
    for (uint32_t y = 0; y < h; ++y)
      for (uint32_t x = 0; x < w; ++x) out.texels[(size_t(z) * h + y) * w + x] = texel(x, y, z);
  return out;
}
}  // namespace

glm::vec4 VolumeLevel::at(int x, int y, int z) const {
  if (x < 0 || y < 0 || z < 0 || x >= int(w) || y >= int(h) || z >= int(d)) return glm::vec4(0.0f);
  return texels[(size_t(z) * h + y) * w + x];
}

glm::vec4 VolumeLevel::clampedAt(int x, int y, int z) const {
  return at(std::clamp(x, 0, int(w) - 1), std::clamp(y, 0, int(h) - 1), std::clamp(z, 0, int(d) - 1));
}

VolumeLevel vctBoxDownsample(const VolumeLevel& s) {
  return makeLevel(std::max(s.w / 2, 1u), std::max(s.h / 2, 1u), std::max(s.d / 2, 1u), [&](uint32_t x, uint32_t y, uint32_t z) {
    glm::vec4 sum(0.0f);
    for (int i = 0; i < 8; ++i) sum += s.at(2 * x + (i & 1), 2 * y + ((i >> 1) & 1), 2 * z + (i >> 2));
    return sum * 0.125f;
  });
}

VolumeLevel vctOpaqueAxisDownsample(const VolumeLevel& s) {
  return makeLevel(std::max(s.w / 2, 1u), std::max(s.h / 2, 1u), std::max(s.d / 2, 1u), [&](uint32_t x, uint32_t y, uint32_t z) {
    glm::vec4 c[8];
    for (int i = 0; i < 8; ++i) c[i] = s.at(2 * x + (i & 1), 2 * y + ((i >> 1) & 1), 2 * z + (i >> 2));
    glm::vec4 best(0.0f);
    for (int axis = 0; axis < 3; ++axis) {
      const int step = 1 << axis;
      glm::vec4 sum(0.0f);
      for (int i = 0; i < 8; ++i)
        if ((i & step) == 0) sum += 0.5f * (over(c[i], c[i | step]) + over(c[i | step], c[i]));
      sum *= 0.25f;
      if (sum.a > best.a) best = sum;
    }
    return best;
  });
}

uint32_t vctSeenMask(float code) { return uint32_t(std::max(code, 1.0f)) - 1u; }
bool vctSeenBothSides(float code) { return vctSeenMask(code) == DYNGI_VCT_SEEN_BOTH_SIDES; }

VolumeLevel vctAnisoDownsample(const VolumeLevel& s, uint32_t sourceSlabWidth, uint32_t destSlabWidth, const VolumeLevel* seenVolume) {
  // The child at c as a cone travelling along `axis` (negative: -axis) sees it (vct_mips.comp, kSharedSource).
  auto seen = [&](const glm::ivec3& c, glm::vec4 texel, uint32_t axis, bool negative) {
    if (!seenVolume) return texel;
    const bool shown = (vctSeenMask(seenVolume->at(c.x, c.y, c.z).a) >> (2 * axis + (negative ? 1 : 0))) & 1u;
    return shown ? texel : glm::vec4(0.0f, 0.0f, 0.0f, texel.a);
  };
  return makeLevel(kSlabs * destSlabWidth, destSlabWidth, destSlabWidth, [&](uint32_t x, uint32_t y, uint32_t z) {
    const uint32_t slab = x / destSlabWidth, axis = slab / 2;
    const bool negative = (slab & 1u) != 0;
    const glm::ivec3 base = 2 * glm::ivec3(x % destSlabWidth, y, z);
    const int offsetX = int((sourceSlabWidth == 0 ? 0 : slab) * sourceSlabWidth);
    const glm::ivec3 along = axis == 0 ? glm::ivec3(1, 0, 0) : (axis == 1 ? glm::ivec3(0, 1, 0) : glm::ivec3(0, 0, 1));
    const glm::ivec3 u = axis == 0 ? glm::ivec3(0, 1, 0) : glm::ivec3(1, 0, 0);
    const glm::ivec3 v = axis == 2 ? glm::ivec3(0, 1, 0) : glm::ivec3(0, 0, 1);
    glm::vec4 sum(0.0f);
    for (int j = 0; j < 4; ++j) {
      const glm::ivec3 c = base + (j & 1) * u + (j >> 1) * v;
      const glm::ivec3 d = c + along;
      const glm::vec4 lo = seen(c, s.at(c.x + offsetX, c.y, c.z), axis, negative), hi = seen(d, s.at(d.x + offsetX, d.y, d.z), axis, negative);
      sum += negative ? over(hi, lo) : over(lo, hi);
    }
    return sum * 0.25f;
  });
}

namespace {
glm::vec4 trilinear(const VolumeLevel& l, const glm::vec3& uvw) {
  const glm::vec3 t = uvw * glm::vec3(l.w, l.h, l.d) - 0.5f;
  const glm::vec3 f0 = glm::floor(t);
  const glm::vec3 f = t - f0;
  const glm::ivec3 i0(f0);
  glm::vec4 sum(0.0f);
  for (int c = 0; c < 8; ++c) {
    const glm::ivec3 o(c & 1, (c >> 1) & 1, c >> 2);
    const float w = (o.x ? f.x : 1.0f - f.x) * (o.y ? f.y : 1.0f - f.y) * (o.z ? f.z : 1.0f - f.z);
    sum += w * l.clampedAt(i0.x + o.x, i0.y + o.y, i0.z + o.z);
  }
  return sum;
}
}  // namespace

glm::vec4 sampleVolumeLod(const std::vector<VolumeLevel>& levels, const glm::vec3& uvw, float lod) {
  const float maxLod = float(levels.size() - 1);
  lod = std::clamp(lod, 0.0f, maxLod);
  const int l0 = int(std::floor(lod));
  const int l1 = std::min(l0 + 1, int(maxLod));
  const float f = lod - float(l0);
  const glm::vec4 a = trilinear(levels[l0], uvw);
  return f > 0.0f ? glm::mix(a, trilinear(levels[l1], uvw), f) : a;
}

namespace {
// Sample s (premultiplied, its opacity over one footprint) over `fraction` of a footprint (vct_cone.glsl's
// vctOverFraction).
glm::vec4 overFraction(const glm::vec4& s, float fraction) {
  const float a = 1.0f - std::pow(std::max(1.0f - s.a, 1e-6f), fraction);
  return glm::vec4(s.a > 1e-6f ? glm::vec3(s) * (a / s.a) : glm::vec3(0.0f), a);
}

// The part a step `steps` footprints long takes from the volume at pos (vct_cone.glsl's vctSample).
glm::vec4 sampleCpu(const std::vector<VolumeLevel>& radiance, const std::vector<VolumeLevel>& aniso, const VctConeParams& p,
                    const glm::vec3& pos, float mip, const glm::vec3& dir, float steps) {
  const glm::vec3 uvw = pos / p.res;
  // The level read (vct_cone.glsl's vctReadLevel): small footprints read the nearest whole one.
  const bool far = mip >= float(DYNGI_VCT_WHOLE_LEVELS_BELOW);
  const float level = far ? mip - p.farNarrowing : std::floor(mip + 0.5f);
  if (far) steps *= std::exp2(p.farNarrowing);  // the step in footprints of the level read
  if (!p.anisotropic) return overFraction(sampleVolumeLod(radiance, uvw, level), steps);
  const glm::vec4 fine = overFraction(sampleVolumeLod(radiance, uvw, 0.0f), steps);
  const float lod = std::max(level - 1.0f, 0.0f);
  const float clampHalf = std::exp2(std::ceil(lod)) / p.res;
  const glm::vec3 w = dir * dir * steps;
  // Each slab's part of the step (its opacity over the fraction w of it), the most opaque in front.
  std::array<glm::vec4, 3> parts;
  for (int axis = 0; axis < 3; ++axis) {
    const int slab = 2 * axis + (dir[axis] < 0.0f ? 1 : 0);
    const float x = std::clamp(uvw.x, clampHalf, 1.0f - clampHalf);
    const glm::vec4 s = sampleVolumeLod(aniso, glm::vec3((float(slab) + x) / float(kSlabs), uvw.y, uvw.z), lod);
    parts[axis] = overFraction(s, w[axis]);
  }
  // The order as vctCombineSlabs takes it, ties included.
  const glm::vec4 hi = parts[0].a >= parts[1].a ? parts[0] : parts[1], lo = parts[0].a >= parts[1].a ? parts[1] : parts[0];
  const glm::vec4 first = hi.a >= parts[2].a ? hi : parts[2], rest = hi.a >= parts[2].a ? parts[2] : hi;
  const glm::vec4 second = rest.a >= lo.a ? rest : lo, third = rest.a >= lo.a ? lo : rest;
  glm::vec4 coarse(0.0f);
  for (const glm::vec4& part : {first, second, third}) coarse += (1.0f - coarse.a) * part;
  return glm::mix(fine, coarse, std::clamp(mip, 0.0f, 1.0f));
}
}  // namespace

glm::vec4 vctConeCpu(const std::vector<VolumeLevel>& radiance, const std::vector<VolumeLevel>& aniso, const VctConeParams& p,
                     const glm::vec3& origin, const glm::vec3& dir, float tanHalf, float rise) {
  glm::vec3 colour(0.0f);
  float alpha = 0.0f;
  float t = p.coneOffset;
  for (int i = 0; i < kMaxSteps; ++i) {
    const float diameter = std::max(1.0f, std::min(2.0f * tanHalf * t, kSurfaceClearance * (p.coneOffset + rise * t)));
    const glm::vec3 pos = origin + t * dir;
    const glm::vec3 beyond = glm::max(glm::max(-pos, pos - glm::vec3(p.res)), glm::vec3(0.0f));
    const float inside = std::clamp(1.0f - std::max(beyond.x, std::max(beyond.y, beyond.z)) / diameter, 0.0f, 1.0f);
    const glm::vec4 part = inside * sampleCpu(radiance, aniso, p, pos, std::log2(diameter), dir, p.coneStep);
    const float a = part.a;
    const glm::vec3 c(part);
    colour += (1.0f - alpha) * c;
    alpha += (1.0f - alpha) * a;
    t += p.coneStep * diameter;
    if (alpha >= 0.99f || t > p.maxDistance || inside <= 0.0f) break;
  }
  return glm::vec4(colour, alpha);
}

}  // namespace dyngi::gi
