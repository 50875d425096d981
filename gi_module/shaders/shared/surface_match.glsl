// How well a neighbour's surface (point qp, normal qn) matches this pixel's (point p, normal n), in 0..1:
// its distance from this pixel's tangent plane (a distance of `planeScale` halves it) times the normals'
// agreement. One test for the passes that carry light between pixels (vct_filter.comp, vct_upsample.comp,
// upsample_indirect.comp), so light stays on its own surface and does not bleed across depth edges or corners.
#ifndef DYNGI_SURFACE_MATCH_GLSL
#define DYNGI_SURFACE_MATCH_GLSL
float surfaceMatch(vec3 p, vec3 n, vec3 qp, vec3 qn, float planeScale) {
  float plane = abs(dot(n, qp - p)) / planeScale;
  // The normals' agreement to the 8th power by squaring: pow() is a log2 and an exp2, four times a pixel
  // in the upsample.
  float agree = max(dot(n, qn), 0.0);
  agree *= agree;
  agree *= agree;
  return exp2(-plane * plane) * agree * agree;
}
#endif
