#version 460
// The clamp compensation's low-resolution blur (after compensate.comp, before filter_columns.comp adds
// it): a 3 x 3 tent (1 2 1) over the texels on the texel's own surface (normals within ~25 degrees,
// points near its tangent plane, the merge filter's test), so each texel's light averages 9 texels'
// turns of the ray spiral.
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
#include "indirect_shared.h"
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = DYNGI_COMPENSATE_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = DYNGI_COMPENSATE_BINDING_TRACED, rgba32ui) uniform readonly uimage2D traced;
layout(set = 0, binding = DYNGI_COMPENSATE_BINDING_OUT, rgba32ui) uniform writeonly uimage2D outBlurred;
layout(push_constant) uniform Push { DYNGI_COMPENSATE_PUSH };
#include "filter_input.glsl"
#include "compensate.glsl"

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  ivec2 low = compensationSize();
  if (texel.x >= low.x || texel.y >= low.y) return;
  uvec4 centre = imageLoad(traced, texel);
  float t = filterViewDepth(centre);
  if (t <= 0.0) {
    imageStore(outBlurred, texel, uvec4(0u));
    return;
  }
  vec3 n = normalize(filterNormal(centre));
  ivec2 px = tracedPixel(texel);
  vec3 x = frame.cameraPos.xyz + t * pixelRay(px);
  float scale = planeTolerance * t * length(pixelRay(px)) * float(DYNGI_COMPENSATE_SCALE);  // taps lie S pixels apart
  vec3 sum = vec3(0.0);
  float wsum = 0.0;
  for (int j = 0; j < 9; ++j) {
    ivec2 o = ivec2(j % 3, j / 3) - 1;
    ivec2 q = clamp(texel + o, ivec2(0), low - 1);
    uvec4 tap = imageLoad(traced, q);
    float tq = filterViewDepth(tap);
    vec3 pq = frame.cameraPos.xyz + tq * pixelRay(tracedPixel(q));
    bool same = tq > 0.0 && dot(n, filterNormal(tap)) >= 0.9 && abs(dot(pq - x, n)) <= scale;
    float w = same ? float((2 - abs(o.x)) * (2 - abs(o.y))) : 0.0;
    sum += w * filterLight(tap);
    wsum += w;
  }
  imageStore(outBlurred, texel, packFilterInput(t, filterPackedNormal(centre), sum / wsum));  // wsum >= 4: the centre counts
}
