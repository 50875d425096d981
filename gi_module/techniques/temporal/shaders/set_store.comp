#version 460
// Keeps the indirect light just gathered for temporal set `set`, with the depth it was seen at, so
// later frames can reproject it. Plain storage buffers (set-major): on a CPU rasterizer they read
// several times faster than image arrays.
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler2D gPosition;
layout(set = 0, binding = 2, rgba32f) uniform readonly image2D raw;
layout(set = 0, binding = 3) writeonly buffer SetIndirect { vec4 setIndirect[]; };
layout(set = 0, binding = 4) writeonly buffer SetDepth { float setDepth[]; };
layout(push_constant) uniform Push { uint set; };
void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  uvec2 size = frame.sizeAndCount.xy;
  if (px.x >= int(size.x) || px.y >= int(size.y)) return;
  vec4 p = texelFetch(gPosition, px, 0);
  float depth = -1.0;
  if (p.w != 0.0) {
    vec4 clip = frame.viewProj * vec4(p.xyz, 1.0);
    depth = clip.z / clip.w;
  }
  uint i = set * size.x * size.y + uint(px.y) * size.x + uint(px.x);
  setIndirect[i] = imageLoad(raw, px);
  setDepth[i] = depth;
}
