// Which cones see an occupied voxel's radiance: the code in the direct-radiance volume's alpha
// (DYNGI_VCT_SEEN_BOTH_SIDES in gi_gpu_types.h; C++: vctSeenMask in vct_cpu.cpp). A one-sided surface
// shows its radiance only to the cones meeting its front; to the others it is black and still opaque,
// as the inside of a solid is.
#ifndef DYNGI_VCT_SEEN_GLSL
#define DYNGI_VCT_SEEN_GLSL

// The code for a voxel with unit normal n; `twoSided`: its fragments face both ways (a wall thinner than
// a voxel). A normal within DYNGI_VCT_PARALLEL of an axis' plane shows the voxel both ways along it.
float vctSeenCode(vec3 n, bool twoSided) {
  if (twoSided) return float(1u + DYNGI_VCT_SEEN_BOTH_SIDES);
  uvec3 plus = uvec3(lessThanEqual(n, vec3(DYNGI_VCT_PARALLEL))), minus = uvec3(greaterThanEqual(n, vec3(-DYNGI_VCT_PARALLEL)));
  uint mask = plus.x | (minus.x << 1) | (plus.y << 2) | (minus.y << 3) | (plus.z << 4) | (minus.z << 5);
  return float(1u + mask);
}

// Per axis, 1 where a cone travelling along +axis (`plus`) or -axis (`minus`) sees the voxel's radiance.
void vctSeenFromCode(float code, out vec3 plus, out vec3 minus) {
  uint mask = uint(max(code, 1.0)) - 1u;
  plus = vec3(uvec3(mask, mask >> 2, mask >> 4) & 1u);
  minus = vec3(uvec3(mask >> 1, mask >> 3, mask >> 5) & 1u);
}

#endif
