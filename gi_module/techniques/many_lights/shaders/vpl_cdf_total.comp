#version 460
#extension GL_GOOGLE_include_directive : require
#include "many_lights_shared.h"
// VPL sampling, step 2 (one thread): running sum over rows; the last entry is the total.
layout(local_size_x = 1) in;
layout(set = 0, binding = DYNGI_VPL_CDF_TOTAL_BINDING_ROW_SUMS) buffer RowSums { float rowSums[]; };  // in: per row; out: inclusive prefix
layout(push_constant) uniform Push { DYNGI_VPL_CDF_TOTAL_PUSH };
void main() {
  float sum = 0.0;
  for (uint r = 0u; r < rows; ++r) {
    sum += rowSums[r];
    rowSums[r] = sum;
  }
}
