#version 460
// VPL sampling, step 3: N stratified samples of the RSM texels, proportional to their luminance.
// VPL flux = texel flux / (N p(texel)), so the VPL set is an unbiased estimate of the reflected flux.
#extension GL_GOOGLE_include_directive : require
#include "many_lights_shared.h"
layout(local_size_x = 64) in;
layout(set = 0, binding = DYNGI_VPL_SAMPLE_BINDING_RSM_POSITION) uniform sampler2DArray rsmPosition;
layout(set = 0, binding = DYNGI_VPL_SAMPLE_BINDING_RSM_NORMAL) uniform sampler2DArray rsmNormal;
layout(set = 0, binding = DYNGI_VPL_SAMPLE_BINDING_RSM_FLUX) uniform sampler2DArray rsmFlux;
layout(set = 0, binding = DYNGI_VPL_SAMPLE_BINDING_ROW_PREFIX) readonly buffer RowPrefix { float rowPrefix[]; };
layout(set = 0, binding = DYNGI_VPL_SAMPLE_BINDING_ROW_CDF) readonly buffer RowCdf { float rowCdf[]; };
layout(set = 0, binding = DYNGI_VPL_SAMPLE_BINDING_VPLS) writeonly buffer Vpls { GpuVpl vpls[]; };
layout(push_constant) uniform Push { DYNGI_VPL_SAMPLE_PUSH };

float hash(uint x) {
  x ^= x >> 16; x *= 0x7feb352du; x ^= x >> 15; x *= 0x846ca68bu; x ^= x >> 16;
  return float(x >> 8) * (1.0 / 16777216.0);
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= count) return;
  uint rows = res * layers;
  float total = rowCdf[rows - 1u];
  GpuVpl v;
  v.position = vec4(0.0, 0.0, 0.0, -1.0);
  v.normal = vec4(0.0, 1.0, 0.0, float(i));
  v.flux = vec4(0.0);
  if (total <= 0.0) { vpls[i] = v; return; }
  float u = (float(i) + hash(i * 2654435761u + seed)) / float(count) * total;
  // Row: first with cdf > u.
  uint lo = 0u, hi = rows - 1u;
  while (lo < hi) { uint mid = (lo + hi) / 2u; if (rowCdf[mid] > u) hi = mid; else lo = mid + 1u; }
  uint row = lo;
  float before = row > 0u ? rowCdf[row - 1u] : 0.0;
  float inRow = u - before;
  uint a = 0u, b = res - 1u;
  while (a < b) { uint mid = (a + b) / 2u; if (rowPrefix[row * res + mid] > inRow) b = mid; else a = mid + 1u; }
  ivec3 t = ivec3(a, row % res, row / res);
  vec4 flux = texelFetch(rsmFlux, t, 0);
  vec4 pos = texelFetch(rsmPosition, t, 0);
  if (flux.a <= 0.0 || pos.w == 0.0) { vpls[i] = v; return; }
  float p = flux.a / total;  // probability of this texel
  v.position = vec4(pos.xyz, 0.0);
  v.normal = vec4(normalize(texelFetch(rsmNormal, t, 0).xyz), float(i));
  v.flux = vec4(flux.rgb / (float(count) * p), flux.a / (float(count) * p));
  vpls[i] = v;
}
