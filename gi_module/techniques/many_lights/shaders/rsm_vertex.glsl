// The RSM's vertex stage, shared by rsm.vert (meshes without a normal texture) and rsm_tangent.vert
// (normal-textured meshes, GpuMesh::tangents at location 3): world position, normal and tangent, the
// transformed texture coordinates (shared/mesh_vertex.glsl).
#include "many_lights_shared.h"
#include "shared/mesh_vertex.glsl"
layout(set = 0, binding = DYNGI_RSM_BINDING_LAYERS) readonly buffer Layers { RsmLayer layers[]; };
layout(push_constant) uniform Push { RsmPush pc; };
void rsmVertex(vec4 objectTangent) { gl_Position = layers[pc.layer].viewProj * meshVertex(pc.model, pc.uvLinear, pc.uvOffset.xy, objectTangent); }
