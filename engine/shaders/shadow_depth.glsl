// One shadow-map layer's fragment: the nearest caster's depth with the depth bias applied, into the depth
// test (gl_FragDepth) and into the r32f lookup layer the lighting pass reads with imageLoad. The bias is a
// rasterizer's, done here so that the test and the lookup see the same value on every GPU (whether
// FragCoord.z includes a pipeline's depth bias is left open by the spec): slope-scaled by the depth's
// screen-space slope, plus a constant number of the float depth's last-place units at its exponent.
// Included by shadow.frag and shadow_masked.frag.
layout(constant_id = 0) const float kBiasConstant = 1.25;
layout(constant_id = 1) const float kBiasSlope = 1.75;
layout(location = 0) out float outDepth;
void writeBiasedDepth() {
  float z = gl_FragCoord.z;
  float slope = max(abs(dFdx(z)), abs(dFdy(z)));
  float ulp = uintBitsToFloat(floatBitsToUint(z) & 0x7f800000u) * exp2(-23.0);  // 2^(exponent - 23)
  float biased = z + kBiasSlope * slope + kBiasConstant * ulp;
  gl_FragDepth = biased;
  outDepth = biased;
}
