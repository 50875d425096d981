#version 460
// One shadow-map layer, an opaque caster (shadow_depth.glsl).
#extension GL_GOOGLE_include_directive : require
#include "shadow_depth.glsl"
void main() { writeBiasedDepth(); }
