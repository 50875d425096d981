// The RSM's vertex stage, shared by rsm.vert (meshes without a normal texture) and rsm_tangent.vert
// (normal-textured meshes, GpuMesh::tangents at location 3): world position, normal and tangent, the
// transformed texture coordinates (shared/mesh_vertex.glsl), and the instance's material constants.
#include "shared/gpu_types.h"
#include "many_lights_shared.h"
#include "shared/mesh_vertex.glsl"
#define DYNGI_DRAW_INSTANCES_BINDING DYNGI_RSM_BINDING_INSTANCES
#include "shared/draw_instances.glsl"
layout(set = 0, binding = DYNGI_RSM_BINDING_LAYERS) readonly buffer Layers { RsmLayer layers[]; };
layout(push_constant) uniform Push { DYNGI_RSM_PUSH };
layout(location = 4) flat out vec4 outBaseColor;  // rgb linear base colour factor, a the alpha mask's threshold
layout(location = 5) flat out vec2 outMaterial;   // metallic factor, normal scale
void rsmVertex(vec4 objectTangent) {
  DrawInstance inst = drawInstance(gl_InstanceIndex);
  gl_Position = layers[layer].viewProj * meshVertex(inst.model, inst.uvLinear, inst.params.zw, objectTangent);
  outBaseColor = inst.baseColor;
  outMaterial = vec2(inst.params.x, unpackHalf2x16(floatBitsToUint(inst.emissive.w)).y);
}
