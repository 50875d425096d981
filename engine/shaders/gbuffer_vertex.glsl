// The G-buffer's vertex stage, shared by gbuffer.vert (meshes without tangents) and gbuffer_tangent.vert
// (normal-textured meshes): world position, normal and tangent, transformed texture coordinates, and the
// instance's material constants for the fragment stage.
#include "shared/gpu_types.h"
#include "shared/mesh_vertex.glsl"
#define DYNGI_DRAW_INSTANCES_BINDING DYNGI_GBUFFER_BINDING_INSTANCES
#include "shared/draw_instances.glsl"

layout(set = 0, binding = DYNGI_GBUFFER_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(location = 4) flat out vec4 outBaseColor;  // gpu::DrawMaterialRecord::baseColor
layout(location = 5) flat out vec3 outEmissive;
layout(location = 6) flat out vec4 outMaterial;   // metallic, roughness, occlusion strength, normal scale

void gbufferVertex(vec4 objectTangent) {
  DrawInstance inst = drawInstance(gl_InstanceIndex);
  gl_Position = frame.viewProj * meshVertex(inst.model, inst.uvLinear, inst.params.zw, objectTangent);
  outBaseColor = inst.baseColor;
  outEmissive = inst.emissive.rgb;
  outMaterial = vec4(inst.params.xy, unpackHalf2x16(floatBitsToUint(inst.emissive.w)));
}
