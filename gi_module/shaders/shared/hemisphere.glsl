// Directions over a hemisphere, shared by the passes that shoot rays or cones from a surface (VCT's
// cones, the clamp compensation's rays).
#ifndef DYNGI_HEMISPHERE_GLSL
#define DYNGI_HEMISPHERE_GLSL
// Direction k of N spread over the hemisphere around +z by cosine (a spiral with the golden angle). Each
// cone gets the solid angle whose projection is its share, pi / N: Omega = pi / (N cos theta), so the
// cones tile the hemisphere (the mean of 1 / cos theta under that spread is 2) and a cone's mean radiance,
// weighted by its projected solid angle over pi, is its part of E / pi both for light from everywhere
// and for a source smaller than the cone. (Equal solid angles, 2 pi / N, would halve a small source seen
// along the normal.)
// `turn` (a fraction of a full turn) rotates the whole spiral about +z.
vec3 cosineSpiral(uint k, uint n, float turn) {
  float u = (float(k) + 0.5) / float(n);
  float r = sqrt(u);
  float phi = float(k) * 2.39996323 + 6.28318531 * turn;
  return vec3(r * cos(phi), r * sin(phi), sqrt(max(1.0 - u, 0.0)));
}
vec3 cosineSpiral(uint k, uint n) { return cosineSpiral(k, n, 0.0); }

// An orthonormal basis around unit n (Duff et al. 2017, "Building an Orthonormal Basis, Revisited").
mat3 basisAround(vec3 n) {
  float s = n.z >= 0.0 ? 1.0 : -1.0;
  float a = -1.0 / (s + n.z);
  float b = n.x * n.y * a;
  return mat3(vec3(1.0 + s * n.x * n.x * a, s * b, -s * n.x), vec3(b, s + n.y * n.y * a, -n.y), n);
}
#endif
