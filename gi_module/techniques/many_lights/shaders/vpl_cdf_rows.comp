#version 460
#extension GL_GOOGLE_include_directive : require
#include "many_lights_shared.h"
// VPL sampling, step 1: per RSM row, the running sum of texel luminance (flux) along the row.
layout(local_size_x = 64) in;
layout(set = 0, binding = DYNGI_VPL_CDF_ROWS_BINDING_RSM_FLUX) uniform sampler2DArray rsmFlux;
layout(set = 0, binding = DYNGI_VPL_CDF_ROWS_BINDING_ROW_PREFIX) writeonly buffer RowPrefix { float rowPrefix[]; };  // per texel, inclusive
layout(set = 0, binding = DYNGI_VPL_CDF_ROWS_BINDING_ROW_SUMS) writeonly buffer RowSums { float rowSums[]; };      // per row
layout(push_constant) uniform Push { DYNGI_VPL_CDF_ROWS_PUSH };
void main() {
  uint row = gl_GlobalInvocationID.x;
  if (row >= res * layers) return;
  uint layer = row / res, y = row % res;
  float sum = 0.0;
  for (uint x = 0u; x < res; ++x) {
    sum += max(texelFetch(rsmFlux, ivec3(x, y, layer), 0).a, 0.0);
    rowPrefix[row * res + x] = sum;
  }
  rowSums[row] = sum;
}
