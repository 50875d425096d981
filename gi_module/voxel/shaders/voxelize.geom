#version 460
// Dominant-axis projection with expansion: each triangle becomes a quad covering the pixel columns its
// projected bounding box touches, so every pixel column the triangle touches gets a fragment (lavapipe
// has no conservative rasterization). The fragment shader then tests voxels exactly.
#extension GL_GOOGLE_include_directive : require
#include "voxel_shared.h"
layout(triangles) in;
layout(triangle_strip, max_vertices = 4) out;
layout(push_constant) uniform Push { VoxelizePush pc; };
layout(location = 0) in vec3 inVoxelPos[];
layout(location = 1) in vec2 inUv[];
layout(location = 2) in vec3 inNormal[];   // the normal texture's frame (voxelize_vertex.glsl), 0 without one
layout(location = 3) in vec4 inTangent[];
layout(location = 4) flat in vec4 inAlbedo[];    // the instance's (voxelize_vertex.glsl)
layout(location = 5) flat in vec4 inEmission[];
layout(location = 6) flat in uvec4 inRange[];
layout(location = 0) flat out vec3 v0;
layout(location = 1) flat out vec3 v1;
layout(location = 2) flat out vec3 v2;
layout(location = 3) flat out vec2 uv0;
layout(location = 4) flat out vec2 uv1;
layout(location = 5) flat out vec2 uv2;
layout(location = 6) flat out uint axis;
layout(location = 7) flat out vec3 n0;
layout(location = 8) flat out vec3 n1;
layout(location = 9) flat out vec3 n2;
layout(location = 10) flat out vec4 t0;
layout(location = 11) flat out vec4 t1;
layout(location = 12) flat out vec4 t2;
layout(location = 13) flat out vec4 albedo;
layout(location = 14) flat out vec4 emission;
layout(location = 15) flat out uvec4 range;

// Projects a voxel-space point to the plane of the dominant axis: returns (u, v) in voxel units.
vec2 project(vec3 p, uint a) { return a == 0u ? p.yz : (a == 1u ? p.zx : p.xy); }

void main() {
  vec3 a = inVoxelPos[0], b = inVoxelPos[1], c = inVoxelPos[2];
  vec3 n = abs(cross(b - a, c - a));
  if (n.x + n.y + n.z == 0.0) return;  // degenerate
  uint ax = (n.x >= n.y && n.x >= n.z) ? 0u : (n.y >= n.z ? 1u : 2u);
  vec2 pa = project(a, ax), pb = project(b, ax), pc2 = project(c, ax);
  // The pixel columns the projected bounding box touches (contact included, as the fragment shader's
  // test counts it), snapped outward to pixel edges: every centre inside is a column to test.
  const float kTouch = 1e-3;
  vec2 lo = floor(min(pa, min(pb, pc2)) - kTouch), hi = floor(max(pa, max(pb, pc2)) + kTouch) + 1.0;
  float res = float(pc.resolution);
  vec2 corners[4] = vec2[](lo, vec2(hi.x, lo.y), vec2(lo.x, hi.y), hi);
  for (int i = 0; i < 4; ++i) {
    v0 = a; v1 = b; v2 = c;
    uv0 = inUv[0]; uv1 = inUv[1]; uv2 = inUv[2];
    n0 = inNormal[0]; n1 = inNormal[1]; n2 = inNormal[2];
    t0 = inTangent[0]; t1 = inTangent[1]; t2 = inTangent[2];
    axis = ax;
    albedo = inAlbedo[0]; emission = inEmission[0]; range = inRange[0];
    gl_Position = vec4(corners[i] / res * 2.0 - 1.0, 0.5, 1.0);
    EmitVertex();
  }
  EndPrimitive();
}
