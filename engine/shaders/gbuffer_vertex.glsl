// The G-buffer's vertex stage, shared by gbuffer.vert (meshes without tangents) and gbuffer_tangent.vert
// (normal-textured meshes): world position, normal and tangent, transformed texture coordinates.
#include "shared/gpu_types.h"
#include "shared/mesh_vertex.glsl"

layout(set = 0, binding = DYNGI_GBUFFER_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(push_constant) uniform Push { GBufferPush pc; };

void gbufferVertex(vec4 objectTangent) { gl_Position = frame.viewProj * meshVertex(pc.model, pc.uvLinear, pc.params.zw, objectTangent); }
