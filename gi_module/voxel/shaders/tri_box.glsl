// Triangle / axis-aligned box overlap by the separating axis theorem (Akenine-Moller), the same test
// as the C++ brute force (gi_module/voxel/tri_box.cpp). `halfSize` may include a tiny epsilon.
#ifndef DYNGI_TRI_BOX_GLSL
#define DYNGI_TRI_BOX_GLSL

bool axisSeparates(vec3 ax, vec3 a, vec3 b, vec3 c, vec3 h) {
  float p0 = dot(a, ax), p1 = dot(b, ax), p2 = dot(c, ax);
  float r = h.x * abs(ax.x) + h.y * abs(ax.y) + h.z * abs(ax.z);
  return min(p0, min(p1, p2)) > r || max(p0, max(p1, p2)) < -r;
}

bool triangleOverlapsBox(vec3 center, vec3 h, vec3 ta, vec3 tb, vec3 tc) {
  vec3 a = ta - center, b = tb - center, c = tc - center;
  if (max(a.x, max(b.x, c.x)) < -h.x || min(a.x, min(b.x, c.x)) > h.x) return false;
  if (max(a.y, max(b.y, c.y)) < -h.y || min(a.y, min(b.y, c.y)) > h.y) return false;
  if (max(a.z, max(b.z, c.z)) < -h.z || min(a.z, min(b.z, c.z)) > h.z) return false;
  vec3 e0 = b - a, e1 = c - b, e2 = a - c;
  vec3 n = cross(e0, e1);
  if (axisSeparates(n, a, b, c, h)) return false;
  vec3 edges[3] = vec3[](e0, e1, e2);
  for (int i = 0; i < 3; ++i) {
    if (axisSeparates(vec3(0.0, -edges[i].z, edges[i].y), a, b, c, h)) return false;
    if (axisSeparates(vec3(edges[i].z, 0.0, -edges[i].x), a, b, c, h)) return false;
    if (axisSeparates(vec3(-edges[i].y, edges[i].x, 0.0), a, b, c, h)) return false;
  }
  return true;
}

#endif
