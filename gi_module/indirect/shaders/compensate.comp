#version 460
// The distance clamp's lost light, given back: the gather's G = cos cos / max(B, d^2) drops
// the fraction 1 - d^2 / B of the light from VPLs closer than sqrt(B), so corners and contact regions
// come out dark. That light comes from surfaces within sqrt(B) of the pixel, which the screen shows, so
// (Kollig and Keller 2004's compensation, estimated in screen space as Novak et al. 2011 do) pixels
// shoot short cosine rays through the depth buffer and add what they lost:
//   E_lost / pi = (1 / N) sum over rays of L(y) max(0, 1 - d^2 / B)
// for a ray that meets the surface y at distance d (cosine sampling: pdf cos / pi). L(y) is the light
// the VPLs at y stand for: y's emission and its direct light from every light (shadowed, as the
// lighting pass computes it), plus, when the VPLs carry more than one bounce, y's indirect light (the
// merge filter's rows pass: an extra bounce of the near field, a small excess). Surfaces off screen or
// hidden behind others are not found: the compensation can miss light, never invent it.
//
// It runs between the merge filter's two passes, so that filter_columns.comp adds it to the indirect
// light it writes: the lighting pass then weighs it by the albedo like the rest, this frame.
// One texel per 4 x 4 pixels (DYNGI_COMPENSATE_SCALE), which is what makes it affordable: the light lost
// varies over sqrt(B), tens of pixels. Every texel shoots `rays` directions of a cosine spiral, turned
// about the normal by a per-texel angle (the same directions everywhere leave bands where they cross an
// edge one after another), each ray with its own start along it; compensate_blur.comp then averages 3 x 3
// texels on the same surface, so a pixel's estimate draws on 9 turns. Output: packed as
// filter_input.glsl (the traced pixel's depth and normal, the light).
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
#include "indirect_shared.h"
#include "shared/lighting.glsl"
#include "shared/hemisphere.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = DYNGI_COMPENSATE_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = DYNGI_COMPENSATE_BINDING_POSITION, rgba32f) uniform readonly image2D gPosition;
layout(set = 0, binding = DYNGI_COMPENSATE_BINDING_NORMAL, rgba16f) uniform readonly image2D gNormal;
layout(set = 0, binding = DYNGI_COMPENSATE_BINDING_ALBEDO, rgba8) uniform readonly image2D gAlbedo;
layout(set = 0, binding = DYNGI_COMPENSATE_BINDING_EMISSIVE, rgba16f) uniform readonly image2D gEmissive;
layout(set = 0, binding = DYNGI_COMPENSATE_BINDING_ROWS, rgba32ui) uniform readonly uimage2D rows;
layout(set = 0, binding = DYNGI_COMPENSATE_BINDING_LIGHTS) readonly buffer Lights { GpuLight lights[]; };
layout(set = 0, binding = DYNGI_COMPENSATE_BINDING_SHADOW_MATRICES) readonly buffer ShadowMatrices { mat4 shadowViewProj[]; };
layout(set = 0, binding = DYNGI_COMPENSATE_BINDING_SHADOW_MAPS, r32f) uniform readonly image2DArray shadowMaps;
layout(set = 0, binding = DYNGI_COMPENSATE_BINDING_OUT, rgba32ui) uniform writeonly uimage2D outTraced;
layout(push_constant) uniform Push { DYNGI_COMPENSATE_PUSH };
#include "shared/shadows.glsl"
#include "filter_input.glsl"
#include "compensate.glsl"

const float PI = 3.14159265358979;
// Steps along a ray of length sqrt(B). A ray that meets a surface at d gives 1 - d^2 / B; stepping finds it
// within a step.
const int kSteps = 6;

// The light the VPLs at y (pixel q, surface point y, normal ny) stand for (see the top).
vec3 vplRadiance(ivec2 q, vec3 y, vec3 ny) {
  vec4 albedoMetal = imageLoad(gAlbedo, q);
  vec4 emissiveOcclusion = imageLoad(gEmissive, q);
  vec3 albedo = albedoMetal.rgb * (1.0 - albedoMetal.a);
  vec3 e = vec3(0.0);
  uint i = 0u;
  do {  // as lighting.comp: a do-while (lavapipe would run a for loop's body once more, masked)
    if (i < lightCount) e += shadowedIrradiance(lights[i], y, ny);
  } while (++i < lightCount);
  vec3 l = emissiveOcclusion.rgb + albedo * e / PI;
  if (includeIndirect != 0u) l += emissiveOcclusion.a * albedo * filterLight(imageLoad(rows, q));
  return l;
}

// Interleaved gradient noise (Jimenez 2014): the texel's turn of the ray spiral about its normal.
float gradientNoise(vec2 p) { return fract(52.9829189 * fract(dot(p, vec2(0.06711056, 0.00583715)))); }

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  ivec2 low = compensationSize();
  if (texel.x >= low.x || texel.y >= low.y) return;
  ivec2 size = ivec2(frame.sizeAndCount.xy);
  ivec2 px = tracedPixel(texel);
  vec4 pos = imageLoad(gPosition, px);
  if (pos.w == 0.0) {
    imageStore(outTraced, texel, uvec4(0u));
    return;
  }
  vec3 x = pos.xyz;
  vec3 n = normalize(imageLoad(gNormal, px).xyz);
  float reach = sqrt(distanceClamp);
  float stepLength = reach / float(kSteps);
  // A ray point counts as inside the surface the depth buffer shows when it lies behind it by less than
  // this (more: it passes behind a foreground object).
  float thickness = 1.5 * stepLength;
  float turn = 6.28318531 * gradientNoise(vec2(texel));
  mat3 basis = basisAround(n) * mat3(cos(turn), sin(turn), 0.0, -sin(turn), cos(turn), 0.0, 0.0, 0.0, 1.0);
  vec3 origin = x + n * (1e-3 * reach) - frame.cameraPos.xyz;
  // The pixel coordinates of a ray point p at view depth t are dot(p - cam, sx / |sx|^2) / t minus a
  // constant (pixel rays are affine in the pixel), and p - cam, t and those dot products are affine along
  // the ray: each step costs two divisions and one load.
  vec3 sx = frame.pixelRayStepX.xyz / dot(frame.pixelRayStepX.xyz, frame.pixelRayStepX.xyz);
  vec3 sy = frame.pixelRayStepY.xyz / dot(frame.pixelRayStepY.xyz, frame.pixelRayStepY.xyz);
  vec2 rayOffset = vec2(dot(frame.pixelRay0.xyz, sx), dot(frame.pixelRay0.xyz, sy));
  mat3 project = transpose(mat3(sx, sy, frame.viewForward.xyz));  // p - cam -> (x, y numerators, view depth)
  vec3 sum = vec3(0.0);
  for (uint i = 0u; i < rays; ++i) {
    vec3 w = basis * cosineSpiral(i, rays);
    float jitter = fract(0.5 + float(i) * 0.618034);  // where along the ray the steps start: each ray its own
    vec3 a0 = project * (origin + w * (jitter * stepLength)), da = project * (w * stepLength);
    bool found = false;
    vec4 hit = vec4(0.0);
    ivec2 hitPixel = px;
    int k = 0;
    do {  // a do-while, as above
      vec3 a = a0 + float(k) * da;
      ivec2 q = ivec2(floor(a.xy / max(a.z, 1e-6) - rayOffset + 0.5));
      bool onScreen = a.z > 0.0 && all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size));
      vec4 s = imageLoad(gPosition, clamp(q, ivec2(0), size - 1));
      float behind = a.z - viewDepthOf(s.xyz);
      bool inside = onScreen && s.w != 0.0 && behind > 0.0 && behind < thickness;
      hit = (!found && inside) ? s : hit;
      hitPixel = (!found && inside) ? q : hitPixel;
      found = found || inside;
    } while (++k < kSteps && !found);
    vec3 d = hit.xyz - x;
    float weight = found ? max(0.0, 1.0 - dot(d, d) / distanceClamp) : 0.0;
    vec3 ny = normalize(imageLoad(gNormal, hitPixel).xyz);
    // The side of y that faces the ray sends its light back along it. A ray that meets the back of what
    // the screen shows (a panel lamp's top, seen from the ceiling above it) gets only its emission:
    // emitters are two-sided (as the path tracer and the VPL sources treat them), the rest unknown.
    if (weight > 0.0) sum += weight * (dot(ny, w) < 0.0 ? vplRadiance(hitPixel, hit.xyz, ny) : imageLoad(gEmissive, hitPixel).rgb);
  }
  vec3 light = rays > 0u ? sum / float(rays) : vec3(0.0);
  imageStore(outTraced, texel, packFilterInput(viewDepthOf(x), packFilterNormal(n), light));
}
