#version 460
// Debug views of the voxel scene, written over the HDR image: `voxels` shows each pixel's first
// occupied voxel with its averaged albedo, lit by its averaged normal; `svo-steps` shows how many
// restarts the SVO march took (blue few, red many).
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
#include "voxel_shared.h"
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = DYNGI_VOXEL_DEBUG_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = DYNGI_VOXEL_DEBUG_BINDING_NODES) readonly buffer Nodes { uint nodes[]; };
layout(set = 0, binding = DYNGI_VOXEL_DEBUG_BINDING_NODE_CELLS) readonly buffer NodeCells { uint nodeCells[]; };
layout(set = 0, binding = DYNGI_VOXEL_DEBUG_BINDING_VOXEL_ATTRIBUTES, rgba32ui) uniform readonly uimage3D voxelAttributes;
layout(set = 0, binding = DYNGI_VOXEL_DEBUG_BINDING_OUT_HDR, rgba32f) uniform writeonly image2D outHdr;
#include "svo_traverse.glsl"
#include "leaf_attributes.glsl"
#include "svo_morton.glsl"
layout(push_constant) uniform Push { DYNGI_VOXEL_DEBUG_PUSH };
void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (px.x >= int(frame.sizeAndCount.x) || px.y >= int(frame.sizeAndCount.y)) return;
  vec2 ndc = (vec2(px) + 0.5) / vec2(frame.sizeAndCount.xy) * 2.0 - 1.0;
  vec4 farP = frame.invViewProj * vec4(ndc, 1.0, 1.0);
  vec3 dirWorld = normalize(farP.xyz / farP.w - frame.cameraPos.xyz);
  vec3 o = (frame.cameraPos.xyz - worldToVoxel.xyz) * worldToVoxel.w;
  float tHit;
  uint steps;
  uint node = svoFirstHit(o, dirWorld, 0.0, 1e30, depth, res, tHit, steps);
  vec3 color = vec3(0.0);
  if (mode == 1u) {
    float s = clamp(float(steps) / 64.0, 0.0, 1.0);
    color = vec3(s, 0.2 * (1.0 - abs(2.0 * s - 1.0)), 1.0 - s) * 0.6;
  } else if (node != 0xFFFFFFFFu) {
    LeafAttributes attr = voxelAttributesAt(svoCellOfMortonCode(SVO_NODE_CELL(nodeCells, node)));
    vec3 n = attr.normalSum;
    float lambert = length(n) > 0.0 ? abs(dot(normalize(n), dirWorld)) : 1.0;
    color = attr.albedo * (0.25 + 0.75 * lambert) * 0.8 + attr.emission;
  }
  imageStore(outHdr, px, vec4(color, 1.0));
}
