// KHR_texture_transform's affine map of texture coordinates, shared by C++ (the path tracer's and the
// VPL shooter's texture lookups) and GLSL (the raster passes' vertex shaders): uv' = L uv + offset, with
// L = R(rotation) S(scale) as the extension defines it (scale, then a rotation counter-clockwise about
// the origin, then the offset). `linear` holds L's rows: (x, y) the first, (z, w) the second.
#ifndef DYNGI_UV_TRANSFORM_H
#define DYNGI_UV_TRANSFORM_H

#ifdef __cplusplus
#include <glm/glm.hpp>
namespace dyngi::gpu {
using glm::vec2;
using glm::vec4;
inline
#endif
vec2 applyUvTransform(vec4 linear, vec2 offset, vec2 uv) {
  return vec2(linear.x * uv.x + linear.y * uv.y, linear.z * uv.x + linear.w * uv.y) + offset;
}

#ifdef __cplusplus
}  // namespace dyngi::gpu
#endif
#endif
