// SVO-restart traversal: GLSL twin of gi_module/voxel/svo_cpu.cpp (keep them in step).
// Requires `nodes[]` (uint) to be declared by the including shader.
#ifndef DYNGI_SVO_TRAVERSE_GLSL
#define DYNGI_SVO_TRAVERSE_GLSL

// Child index (x | y<<1 | z<<2) of the cell holding p; a point on a split plane belongs to the side the
// ray is moving into, so a restart exactly on a face never re-enters the cell it just left.
uint childOf(vec3 p, vec3 mid, vec3 dir) {
  uint c = 0u;
  if (p.x > mid.x || (p.x == mid.x && dir.x >= 0.0)) c |= 1u;
  if (p.y > mid.y || (p.y == mid.y && dir.y >= 0.0)) c |= 2u;
  if (p.z > mid.z || (p.z == mid.z && dir.z >= 0.0)) c |= 4u;
  return c;
}

// First occupied leaf along the ray o + t dir (dir unit, voxel units) for t in [tMin, tMax).
// Returns the leaf's node index or 0xFFFFFFFF; `tHit` is where the ray enters that leaf.
// SVO-restart: descend from the root to the leaf holding the current point; an empty node is left
// through its box (a point on a face belongs to the cell the ray moves into) and the descent restarts.
uint svoFirstHit(vec3 o, vec3 dir, float tMin, float tMax, uint depth, float res, out float tHit, out uint steps) {
  steps = 0u;
  tHit = 0.0;
  vec3 invDir = vec3(dir.x != 0.0 ? 1.0 / dir.x : 1e30, dir.y != 0.0 ? 1.0 / dir.y : 1e30, dir.z != 0.0 ? 1.0 / dir.z : 1e30);
  vec3 t0 = (vec3(0.0) - o) * invDir, t1 = (vec3(res) - o) * invDir;
  vec3 tn = min(t0, t1), tf = max(t0, t1);
  float t = max(tMin, max(tn.x, max(tn.y, tn.z)));
  float tEnd = min(tMax, min(tf.x, min(tf.y, tf.z)));
  for (uint iter = 0u; iter < 4096u && t < tEnd; ++iter) {
    ++steps;
    vec3 p = o + dir * t;
    uint node = 0u;
    vec3 lo = vec3(0.0);
    float size = res;
    for (uint level = 0u;; ++level) {
      uint w = nodes[node];
      if ((w & DYNGI_SVO_FLAG) == 0u) break;
      if (level == depth || (w & DYNGI_SVO_GROUP_MASK) == 0u) {
        tHit = t;
        return node;
      }
      size *= 0.5;
      uint c = childOf(p, lo + size, dir);
      lo += vec3(c & 1u, (c >> 1) & 1u, (c >> 2) & 1u) * size;
      node = 8u * (w & DYNGI_SVO_GROUP_MASK) + c;
    }
    vec3 far = vec3(dir.x >= 0.0 ? lo.x + size : lo.x, dir.y >= 0.0 ? lo.y + size : lo.y, dir.z >= 0.0 ? lo.z + size : lo.z);
    vec3 te = (far - o) * invDir;
    t = max(min(te.x, min(te.y, te.z)), t) + max(1e-5, t * 4e-7);
  }
  return 0xFFFFFFFFu;
}

// True when the segment a -> b (voxel units), shrunk by `eps` at both ends, passes through an occupied
// leaf (or a node that could not be subdivided: conservative): the first-hit march over that interval.
bool svoOccluded(vec3 a, vec3 b, float eps, uint depth, float res, out uint steps) {
  steps = 0u;
  vec3 d = b - a;
  float len = length(d);
  if (len <= 2.0 * eps) return false;
  float tHit;
  return svoFirstHit(a, d / len, eps, len - eps, depth, res, tHit, steps) != 0xFFFFFFFFu;
}

#endif
