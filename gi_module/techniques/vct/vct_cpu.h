#pragma once
// C++ twins of the voxel cone tracer's GPU work (techniques/vct/shaders): the mip chain's box and
// per-direction filters and the cone march with the sampler's quadrilinear filtering. Tests hold the GPU
// equal to them; they are not fast.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace dyngi::gi {

// One level of a 3D RGBA volume, x fastest (as readbackImageLevel returns it).
struct VolumeLevel {
  uint32_t w = 0, h = 0, d = 0;
  std::vector<glm::vec4> texels;
  glm::vec4 at(int x, int y, int z) const;         // transparent black outside
  glm::vec4 clampedAt(int x, int y, int z) const;  // the nearest texel (the sampler's clamp to edge)
};

// The isotropic next level: the mean of each texel's 8 children (vct_mips.comp, not anisotropic).
VolumeLevel vctBoxDownsample(const VolumeLevel& source);
// The isotropic next level with each texel's opacity from its most opaque axis (opaqueAxisMips).
VolumeLevel vctOpaqueAxisDownsample(const VolumeLevel& source);
// The next level of the six-direction atlas (vct_mips.comp, anisotropic): from one isotropic source
// (sourceSlabWidth 0) with which cones see each voxel (`seen`: the direct-radiance volume, its alpha
// the code of vct_seen.glsl; a one-sided voxel's radiance shows only to cones meeting its front), or from
// the atlas level below (seen null).
VolumeLevel vctAnisoDownsample(const VolumeLevel& source, uint32_t sourceSlabWidth, uint32_t destSlabWidth,
                               const VolumeLevel* seen = nullptr);
// The mask of vct_seen.glsl's code (bit 2 axis: seen travelling along +axis, 2 axis + 1: along -axis).
uint32_t vctSeenMask(float code);
// True for a two-sided voxel's code (seen from all six directions).
bool vctSeenBothSides(float code);

// textureLod with linear filtering and mip interpolation, clamped to the edge.
glm::vec4 sampleVolumeLod(const std::vector<VolumeLevel>& levels, const glm::vec3& uvw, float lod);

struct VctConeParams {
  float res = 128, maxDistance = 128, aoDistance = 19, coneOffset = 1, coneStep = 0.5f, farNarrowing = 0;
  bool anisotropic = false;
};
// vctCone (vct_cone.glsl): radiance (rgb) and opacity (a) along a cone from `origin` (voxel units).
// `radiance`: level 0 and the isotropic mips; `aniso`: the atlas levels (anisotropic only).
glm::vec4 vctConeCpu(const std::vector<VolumeLevel>& radiance, const std::vector<VolumeLevel>& aniso, const VctConeParams& p,
                     const glm::vec3& origin, const glm::vec3& dir, float tanHalf, float rise = 1.0f);

}  // namespace dyngi::gi
