// glTF's normal texture, shared by C++ (the path tracer's and the VPL shooter's SceneSurfaces) and GLSL
// (the G-buffer): the shading normal from the interpolated normal n (unit), the tangent (xyz, w the
// bitangent's sign) and the texel (rgb in [0, 1]), its xy scaled by `scale`. A tangent along n (no frame)
// leaves n as it is.
#ifndef DYNGI_NORMAL_MAP_H
#define DYNGI_NORMAL_MAP_H

#ifdef __cplusplus
#include <glm/glm.hpp>
namespace dyngi::gpu {
using glm::cross;
using glm::dot;
using glm::normalize;
using glm::vec3;
using glm::vec4;
inline
#endif
vec3 perturbNormal(vec3 n, vec4 tangent, vec3 texel, float scale) {
  vec3 t = vec3(tangent.x, tangent.y, tangent.z);
  t = t - n * dot(n, t);
  if (!(dot(t, t) > 1e-12f)) return n;
  t = normalize(t);
  const vec3 b = cross(n, t) * (tangent.w < 0.0f ? -1.0f : 1.0f);
  const vec3 m = texel * 2.0f - vec3(1.0f);
  return normalize(t * (m.x * scale) + b * (m.y * scale) + n * m.z);
}

#ifdef __cplusplus
}  // namespace dyngi::gpu
#endif
#endif
