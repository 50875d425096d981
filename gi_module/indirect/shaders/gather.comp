#version 460
// The plain interleaved gather (gather.glsl): writes each pixel's light packed with its depth and normal
// for the filter (filter_input.glsl). The many-lights technique's gather.
#extension GL_GOOGLE_include_directive : require
#include "gather.glsl"

void main() {
  ivec2 px;
  vec3 light;
  float depth;
  uvec2 packedNormal;
  if (!gatherPixel(px, light, depth, packedNormal)) return;
  imageStore(outRaw, px, depth > 0.0 ? packFilterInput(depth, packedNormal, light) : uvec4(0u));
}
