// Light units and attenuation: GLSL twin of engine/scene/light_units.cpp (keep them in step).
#ifndef DYNGI_LIGHTING_GLSL
#define DYNGI_LIGHTING_GLSL

float spotFalloff(float cosAngle, float cosOuter, float cosInner) {
  float t = clamp((cosAngle - cosOuter) / max(cosInner - cosOuter, 1e-4), 0.0, 1.0);
  return t * t;
}

float rangeWindow(float d, float range) {
  if (range <= 0.0) return 1.0;
  float r = d / range;
  float w = clamp(1.0 - r * r * r * r, 0.0, 1.0);
  return w * w;
}

// Unshadowed irradiance at p (normal n) from light L; also returns the unit direction to the light.
vec3 lightIrradiance(GpuLight L, vec3 p, vec3 n, out vec3 toLightDir, out float dist) {
  vec3 radiant = L.radiance.rgb * L.radiance.w;
  int type = int(L.positionType.w);
  if (type == DYNGI_LIGHT_DIRECTIONAL) {
    toLightDir = -L.directionRange.xyz;
    dist = 1e30;
    return radiant * max(0.0, dot(n, toLightDir));
  }
  vec3 d = L.positionType.xyz - p;
  float d2 = max(dot(d, d), 1e-8);
  dist = sqrt(d2);
  toLightDir = d / dist;
  float e = max(0.0, dot(n, toLightDir)) / d2 * rangeWindow(dist, L.directionRange.w);
  if (type == DYNGI_LIGHT_SPOT) e *= spotFalloff(dot(-toLightDir, L.directionRange.xyz), L.cone.x, L.cone.y);
  return radiant * e;
}

#endif
