#version 460
// The voxelizer for draws whose triangles all span at most VoxelScene::kComputeVoxelizeSpan voxels a
// side (many small instances: debris, foliage, a field of props): one invocation per instance and
// triangle tests the few voxels of its bounding box exactly and appends what voxelize.frag would. The
// raster path spends a geometry-shader quad and its pixels on each such triangle.
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
#include "voxel_shared.h"
#include "shared/uv_transform.h"
#define DYNGI_DRAW_INSTANCES_BINDING DYNGI_VOXELIZE_BINDING_INSTANCES
#include "shared/draw_instances.glsl"
#include "tri_box.glsl"

layout(local_size_x = 64) in;
layout(push_constant) uniform Push { VoxelizePush pc; };
// Material variants as voxelize.frag's (VoxelScene::voxelizeSmallPipelineFor); no normal textures here.
layout(constant_id = 0) const bool kBaseColorTexture = true;
layout(constant_id = 1) const bool kEmissiveTexture = true;
layout(constant_id = 2) const bool kMetallicRoughnessTexture = true;
layout(constant_id = 3) const bool kAlphaMask = false;
const bool kNormalTexture = false;
layout(set = 0, binding = DYNGI_VOXELIZE_BINDING_FRAGMENTS) buffer Fragments { uvec4 fragments[]; };
layout(set = 0, binding = DYNGI_VOXELIZE_BINDING_COUNTERS) buffer Counters { uint counters[]; };
layout(set = 0, binding = DYNGI_VOXELIZE_BINDING_BASE_COLOR_TEX) uniform sampler2D baseColorTex;
layout(set = 0, binding = DYNGI_VOXELIZE_BINDING_EMISSIVE_TEX) uniform sampler2D emissiveTex;
layout(set = 0, binding = DYNGI_VOXELIZE_BINDING_METALLIC_ROUGHNESS_TEX) uniform sampler2D metallicRoughnessTex;
layout(set = 0, binding = DYNGI_VOXELIZE_BINDING_NORMAL_TEX) uniform sampler2D normalTex;
layout(set = 0, binding = DYNGI_VOXELIZE_BINDING_RANGES) readonly buffer Ranges { VoxelizeRange ranges[]; };
layout(set = 0, binding = DYNGI_VOXELIZE_BINDING_VERTICES) readonly buffer Vertices { float vertexFloats[]; };  // render::GpuVertex
layout(set = 0, binding = DYNGI_VOXELIZE_BINDING_INDICES) readonly buffer Indices { uint indices[]; };
#include "voxel_fragment.glsl"

const uint kVertexFloats = 8u;  // GpuVertex: position, normal, uv

void main() {
  uint id = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * 64u + gl_LocalInvocationID.x;  // 2-D past the device's x limit
  if (id >= pc.instanceCount * pc.triangleCount) return;
  uint slot = pc.firstInstance + id / pc.triangleCount, triangle = id % pc.triangleCount;
  DrawInstance inst = drawInstance(slot);
  mat4 modelToVoxel = pc.worldToVoxel * inst.model;
  vec3 p[3];
  vec2 uv[3];
  for (int k = 0; k < 3; ++k) {
    uint base = indices[3u * triangle + uint(k)] * kVertexFloats;
    vec3 position = vec3(vertexFloats[base], vertexFloats[base + 1u], vertexFloats[base + 2u]);
    p[k] = (modelToVoxel * vec4(position, 1.0)).xyz;
    uv[k] = applyUvTransform(inst.uvLinear, inst.params.zw, vec2(vertexFloats[base + 6u], vertexFloats[base + 7u]));
  }
  vec3 n = cross(p[1] - p[0], p[2] - p[0]);
  if (n.x == 0.0 && n.y == 0.0 && n.z == 0.0) return;  // degenerate, as the geometry shader drops it
  VoxelizeRange r = ranges[slot];
  VoxelTriangle t = VoxelTriangle(p[0], p[1], p[2], uv[0], uv[1], uv[2], vec3(0.0), vec3(0.0), vec3(0.0), vec4(0.0), vec4(0.0), vec4(0.0),
                                  vec4(inst.baseColor.rgb, inst.params.x), vec4(inst.emissive.rgb, inst.baseColor.a),
                                  uvec4(r.firstSlot, r.capacity, r.counterIndex, 0u));
  vec3 nrm = normalize(n);
  int top = int(pc.resolution) - 1;
  ivec3 lo = max(ivec3(floor(min(p[0], min(p[1], p[2])) - kVoxelTouchEps)), ivec3(0));
  ivec3 hi = min(ivec3(floor(max(p[0], max(p[1], p[2])) + kVoxelTouchEps)), ivec3(top));
  for (int z = lo.z; z <= hi.z; ++z)
    for (int y = lo.y; y <= hi.y; ++y)
      for (int x = lo.x; x <= hi.x; ++x)
        if (triangleOverlapsBox(vec3(x, y, z) + 0.5, vec3(0.5 + kVoxelTouchEps), p[0], p[1], p[2])) appendVoxelFragment(ivec3(x, y, z), t, nrm);
}
