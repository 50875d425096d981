#version 460
// The traced pixels that get no new cones this frame (the trace spread over traceFrames frames,
// vct_trace_phase.glsl) take last frame's value at the point their surface was seen from then: this
// pixel's surface point is projected through last frame's camera, and the traced pixel nearest to where it
// landed counts if it saw the same surface (the filter's and upsample's surface test).
//
// That value is up to traceFrames - 1 frames old: the light it shows lags by as much. Changes that would
// make it wrong at once (a light switched, a jump) drop every old value (VoxelConeTracing::dropTraceHistory).
// (Tried: comparing this frame's traced neighbours with their values last frame and dropping, or scaling,
// the old value where they changed. Scaling fed back on itself, a neighbour's last value being a scaled
// one, and diverged; dropping halved the first frame's error after a jump but doubled the change a frame
// under a camera pan, the neighbours' last values coming from pixels whose cones were turned otherwise.)
//
// A value that cannot be carried over (disoccluded, off screen last frame, not traced for maxAge frames,
// no history) is marked missing (alpha -1): the filter and the upsample leave it out and take the light
// from the neighbours traced this frame, of which every 2 x 2 window holds one.
// Every pixel also records its surface (vct_surface.glsl) for the filter, the upsample and next frame.
// Runs after vct_trace.comp and writes only the pixels it did not trace.
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
#include "vct_shared.h"
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = DYNGI_VCT_REPROJECT_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = DYNGI_VCT_REPROJECT_BINDING_G_POSITION, rgba32f) uniform readonly image2D gPosition;
layout(set = 0, binding = DYNGI_VCT_REPROJECT_BINDING_G_NORMAL, rgba16f) uniform readonly image2D gNormal;
layout(set = 0, binding = DYNGI_VCT_REPROJECT_BINDING_PREVIOUS_DIFFUSE, rgba16f) uniform readonly image2D previousDiffuse;
layout(set = 0, binding = DYNGI_VCT_REPROJECT_BINDING_PREVIOUS_SPECULAR, rgba16f) uniform readonly image2D previousSpecular;
layout(set = 0, binding = DYNGI_VCT_REPROJECT_BINDING_PREVIOUS_SURFACE, rgba32ui) uniform readonly uimage2D previousSurface;
layout(set = 0, binding = DYNGI_VCT_REPROJECT_BINDING_OUT_DIFFUSE, rgba16f) uniform writeonly image2D outDiffuse;
layout(set = 0, binding = DYNGI_VCT_REPROJECT_BINDING_OUT_SPECULAR, rgba16f) uniform writeonly image2D outSpecular;
layout(set = 0, binding = DYNGI_VCT_REPROJECT_BINDING_OUT_SURFACE, rgba32ui) uniform writeonly uimage2D outSurface;
layout(push_constant) uniform Push { DYNGI_VCT_REPROJECT_PUSH };
#include "shared/surface_match.glsl"
#include "vct_trace_phase.glsl"
#include "vct_surface.glsl"

// Last frame's traced pixel that saw surface point p (normal n), if any: `from` its coordinates.
bool lastFrameAt(vec3 p, vec3 n, float planeScale, ivec2 full, ivec2 low, out ivec2 from) {
  from = ivec2(-1);
  vec4 clip = previousViewProj * vec4(p, 1.0);
  if (history == 0u || clip.w <= 0.0) return false;
  int s = int(traceScale), h = s / 2;
  vec2 pixel = (clip.xy / clip.w * 0.5 + 0.5) * vec2(full) - 0.5;  // last frame's full-resolution pixel
  from = ivec2(floor((pixel - float(h)) / float(s) + 0.5));
  if (any(lessThan(from, ivec2(0))) || any(greaterThanEqual(from, low))) return false;
  vec3 qp, qn;
  return vctUnpackSurface(imageLoad(previousSurface, from), qp, qn) && surfaceMatch(p, n, qp, qn, planeScale) > 0.5;
}

void main() {
  ivec2 q = ivec2(gl_GlobalInvocationID.xy);
  ivec2 low = imageSize(outDiffuse);
  if (any(greaterThanEqual(q, low))) return;
  ivec2 full = ivec2(frame.sizeAndCount.xy);
  int s = int(traceScale), h = s / 2;
  vec4 pos = imageLoad(gPosition, min(q * s + h, full - 1));
  bool traced = vctTracedThisFrame(q);
  if (pos.w == 0.0) {  // background: as the trace writes it
    imageStore(outSurface, q, uvec4(0u));
    if (!traced) {
      imageStore(outDiffuse, q, vec4(0.0, 0.0, 0.0, 1.0));
      imageStore(outSpecular, q, vec4(0.0));
    }
    return;
  }
  vec3 n = normalize(imageLoad(gNormal, min(q * s + h, full - 1)).xyz);
  imageStore(outSurface, q, vctPackSurface(pos.xyz, n));
  if (traced) return;
  // Within about one traced pixel's footprint of this pixel's plane: the same surface.
  float scale = 0.01 * float(s) * max(length(pos.xyz - frame.cameraPos.xyz), 1e-4);
  vec4 diffuse = vec4(0.0, 0.0, 0.0, -1.0), specular = vec4(0.0, 0.0, 0.0, -1.0);
  ivec2 from;
  if (lastFrameAt(pos.xyz, n, scale, full, low, from)) {
    vec4 d = imageLoad(previousDiffuse, from), sp = imageLoad(previousSpecular, from);
    // Specular alpha counts the frames since the value was traced.
    if (d.a >= 0.0 && sp.a + 1.0 <= float(maxAge)) {
      diffuse = d;
      specular = vec4(sp.rgb, sp.a + 1.0);
    }
  }
  imageStore(outDiffuse, q, diffuse);
  imageStore(outSpecular, q, specular);
}
