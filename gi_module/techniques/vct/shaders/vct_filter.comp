#version 460
// The traced diffuse light (E / pi, AO in alpha) averaged over a line of traced pixels along one axis (run
// along x, then along y: a 2D window for 2 (2r + 1) taps instead of (2r + 1)^2), each weighted by a tent
// in its distance and by how well its surface matches this one's (shared/surface_match.glsl, the upsample's
// test), so light stays on its own surface. The traced pixels turned their cone sets by different angles
// (vct_trace.comp): the average is the hemisphere seen through all of their cones, where one pixel's few
// cones would miss the same directions over a face. A value vct_reproject.comp marked missing (alpha < 0)
// counts for nothing; where a whole window is missing the output is missing too, and the pass along the
// other axis fills it.
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
#include "vct_shared.h"
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = DYNGI_VCT_FILTER_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = DYNGI_VCT_FILTER_BINDING_SURFACE, rgba32ui) uniform readonly uimage2D surfaces;  // vct_surface.glsl
layout(set = 0, binding = DYNGI_VCT_FILTER_BINDING_IN, rgba16f) uniform readonly image2D traced;
layout(set = 0, binding = DYNGI_VCT_FILTER_BINDING_OUT, rgba16f) uniform writeonly image2D filtered;
layout(push_constant) uniform Push { DYNGI_VCT_FILTER_PUSH };
#include "vct_surface.glsl"
#include "shared/surface_match.glsl"

void main() {
  ivec2 q = ivec2(gl_GlobalInvocationID.xy);
  ivec2 low = imageSize(traced);
  if (any(greaterThanEqual(q, low))) return;
  vec4 centre = imageLoad(traced, q);
  vec3 p, n;
  if (!vctUnpackSurface(imageLoad(surfaces, q), p, n)) {
    imageStore(filtered, q, centre);
    return;
  }
  // The window spans radius x traceScale pixels: the plane test scales with the pixels between taps.
  float scale = 0.01 * float(traceScale) * max(length(p - frame.cameraPos.xyz), 1e-4);
  vec4 sum = vec4(0.0);
  float total = 0.0;
  for (int i = -radius; i <= radius; ++i) {
    ivec2 o = q + i * ivec2(axisX, axisY);
    if (any(lessThan(o, ivec2(0))) || any(greaterThanEqual(o, low))) continue;
    vec3 qp, qn;
    if (!vctUnpackSurface(imageLoad(surfaces, o), qp, qn)) continue;
    float tent = 1.0 - float(abs(i)) / float(radius + 1);
    vec4 value = imageLoad(traced, o);
    float w = value.a < 0.0 ? 0.0 : tent * surfaceMatch(p, n, qp, qn, scale);
    sum += w * value;
    total += w;
  }
  imageStore(filtered, q, total > 1e-4 ? sum / total : (centre.a < 0.0 ? vec4(0.0, 0.0, 0.0, -1.0) : centre));
}
