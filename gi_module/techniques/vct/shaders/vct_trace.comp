#version 460
// The screen's cones: for one pixel in traceScale x traceScale (the one at the block's centre), the
// indirect diffuse light (E / pi, from `cones` diffuse cones) with ambient occlusion in alpha, and the
// specular cone along the reflected view ray, its aperture from the G-buffer roughness (alpha = r^2).
// vct_upsample.comp takes both to full resolution. With traceFrames > 1 this frame's share of the traced
// pixels only (vct_trace_phase.glsl); vct_reproject.comp fills in the others.
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
#include "vct_shared.h"
layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const bool kAnisotropic = false;
layout(constant_id = 1) const bool kSpecular = true;
layout(set = 0, binding = DYNGI_VCT_TRACE_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = DYNGI_VCT_TRACE_BINDING_G_POSITION, rgba32f) uniform readonly image2D gPosition;
layout(set = 0, binding = DYNGI_VCT_TRACE_BINDING_G_NORMAL, rgba16f) uniform readonly image2D gNormal;
layout(set = 0, binding = DYNGI_VCT_TRACE_BINDING_RADIANCE) uniform sampler3D vctRadiance;
layout(set = 0, binding = DYNGI_VCT_TRACE_BINDING_ANISO) uniform sampler3D vctAniso;
layout(set = 0, binding = DYNGI_VCT_TRACE_BINDING_OUT_DIFFUSE, rgba16f) uniform writeonly image2D outDiffuse;
layout(set = 0, binding = DYNGI_VCT_TRACE_BINDING_OUT_SPECULAR, rgba16f) uniform writeonly image2D outSpecular;
layout(push_constant) uniform Push { DYNGI_VCT_TRACE_PUSH };
#include "vct_cone.glsl"
#include "vct_trace_phase.glsl"

// The narrowest specular cone: below a few degrees a cone only samples level 0 for many steps.
const float kMinSpecularTan = 0.03;

void main() {
  ivec2 q = vctTracedPixel(gl_GlobalInvocationID);
  if (any(greaterThanEqual(q, imageSize(outDiffuse)))) return;
  ivec2 full = ivec2(frame.sizeAndCount.xy);
  ivec2 px = min(q * int(traceScale) + int(traceScale / 2u), full - 1);
  vec4 pos = imageLoad(gPosition, px);
  if (pos.w == 0.0) {  // background: nothing to light (alpha 0 tells the upsample to skip it)
    imageStore(outDiffuse, q, vec4(0.0, 0.0, 0.0, 1.0));
    imageStore(outSpecular, q, vec4(0.0));  // alpha: frames since traced (vct_reproject.comp)
    return;
  }
  vec4 nr = imageLoad(gNormal, px);
  vec3 n = normalize(nr.xyz);
  vec3 p = (pos.xyz - volume.xyz) / volume.w;
  float ao;
  // Each traced pixel turns its cones about the normal by a golden-ratio dither of its coordinates
  // (Roberts' R2), which spreads the turns evenly over any window of neighbours: vct_filter.comp's average
  // of them sees the hemisphere through many more directions than one pixel's few cones. Only the
  // azimuth turns: jittering the elevations too (the widths follow them) cost lavapipe another 15 percent
  // of the frame at 768^2. Turning costs about 11 percent there (neighbours' cones read different texels;
  // a turn shared by a row of 8 pixels cost as much and filtered worse). `--diffuse-filter-radius 0` leaves the
  // turn out, and every pixel then marches every cone (nothing would bring the rows' halves together).
  // Rows take turns over the cone set (VctOptions::coneInterleave): a row of the dispatch, a row of
  // lanes, holds traced pixels of one row whether the trace is spread over frames or not, so every lane
  // marches the same cones, with the same footprints and steps, and a pixel's cones do not depend on
  // traceFrames (a still view converges to the every-frame image).
  // A frame that traces a quarter of the lattice with nothing carried over (coneRowShift) traces rows
  // of one parity only: pairs of rows take the turns then, so its pixels hold every cone between them.
  uint stride = max(coneInterleave, 1u);
  float turn = turnCones != 0u ? fract(0.7548776662 * float(q.x) + 0.5698402910 * float(q.y)) : 0.0;
  vec3 diffuse = vctDiffuse(p, n, turn, (uint(q.y) >> coneRowShift) % stride, stride, ao);
  imageStore(outDiffuse, q, vec4(diffuse, ao));
  // A pixel at least specularConeBelow rough takes the diffuse light as its specular (VctOptions::
  // specularConeBelow; the upsample blends the filtered diffuse in): it marches no cone, and a row of
  // lanes that all are skips the cone's loops. Stored here too for the smoother pixels next to it.
  vec3 specular = diffuse;
  if (kSpecular && nr.w < specularConeBelow) {
    vec3 v = normalize(frame.cameraPos.xyz - pos.xyz);
    // The GGX lobe's dominant direction leans from the mirror direction towards the normal as the
    // roughness grows (Lagarde and de Rousiers 2014, "Moving Frostbite to PBR"): a rough surface's wide
    // cone then rises from it fast enough to open up, instead of grazing it.
    float rough = nr.w;
    vec3 r = normalize(mix(n, reflect(-v, n), (1.0 - rough) * (sqrt(1.0 - rough) + rough)));
    float tanHalf = clamp(rough * rough, kMinSpecularTan, 1.0);
    float occ;
    // Its footprints are the lobe's own: the far narrowing is for the diffuse cones (a rough lobe read
    // narrower reflected sharper than a smoother one).
    specular = vctCone(p + n * coneOffset, r, tanHalf, max(dot(r, n), 0.0), maxDistance, 0.0, occ).rgb;
  }
  imageStore(outSpecular, q, vec4(specular, 0.0));
}
