#include "dyngi/engine/scene/alpha_cut.h"

#include <algorithm>

#include "shared/uv_transform.h"

namespace dyngi::scene {

float alphaMaskThreshold(const Material& m) { return m.alphaCutoff / std::max(m.baseColor.a, 1e-6f); }

AlphaCut AlphaCut::of(const Material& m) {
  AlphaCut c;
  if (!m.alphaMask) return c;
  c.masked = true;
  c.texture = m.baseColorTexture;
  c.uvLinear = m.uvTransform.linear();
  c.uvOffset = m.uvTransform.offset;
  c.threshold = alphaMaskThreshold(m);
  return c;
}

bool AlphaCut::cuts(const AssetStore& assets, const MeshData& m, size_t primitive, float u, float v) const {
  if (!masked) return false;
  float alpha = 1.0f;
  if (texture != kNoTexture && texture < assets.textureCount()) {
    const size_t t = primitive * 3;
    glm::vec2 uv(0.0f);
    if (t + 2 < m.indices.size() && m.uvs.size() == m.positions.size()) {
      const uint32_t i0 = m.indices[t], i1 = m.indices[t + 1], i2 = m.indices[t + 2];
      if (i0 < m.uvs.size() && i1 < m.uvs.size() && i2 < m.uvs.size()) uv = (1.0f - u - v) * m.uvs[i0] + u * m.uvs[i1] + v * m.uvs[i2];
    }
    alpha = sampleTexture(assets.texture(texture), gpu::applyUvTransform(uvLinear, uvOffset, uv)).a;
  }
  return alpha < threshold;
}

}  // namespace dyngi::scene
