#pragma once
// A masked material's cut (glTF alphaMode MASK) as the CPU's rays test it: the base colour texture's
// alpha at a hit's uv under the threshold. Embree's filter, picking and the change tracker (a cut that
// changes moves surfaces as far as rays are concerned) read this one definition; the raster passes do
// the same test in GLSL with alphaMaskThreshold() in their push constants.
#include <cstddef>

#include <glm/glm.hpp>

#include "dyngi/engine/scene/assets.h"
#include "dyngi/engine/scene/components.h"

namespace dyngi::scene {

// The cut as a threshold on the texture's alpha: cutoff / the alpha factor (above 1, all is cut).
float alphaMaskThreshold(const Material& material);

struct AlphaCut {
  bool masked = false;
  TextureId texture = kNoTexture;
  glm::vec4 uvLinear{1.0f, 0.0f, 0.0f, 1.0f};  // KHR_texture_transform
  glm::vec2 uvOffset{0.0f};
  float threshold = 0.0f;

  static AlphaCut of(const Material& material);
  // True where triangle `primitive` of `mesh` is cut at barycentrics (u, v) (Embree's: the weights of
  // its second and third vertex).
  bool cuts(const AssetStore& assets, const MeshData& mesh, size_t primitive, float u, float v) const;
  // Same cut: both unmasked, or masked alike.
  bool operator==(const AlphaCut& o) const {
    if (!masked || !o.masked) return masked == o.masked;
    return texture == o.texture && uvLinear == o.uvLinear && uvOffset == o.uvOffset && threshold == o.threshold;
  }
};

}  // namespace dyngi::scene
