// Which traced pixels get new cones this frame when the trace is spread over traceFrames frames
// (vct_trace.comp traces them, vct_reproject.comp carries the others over from last frame). Every 2 x 2
// block of traced pixels is one lattice cell; its four pixels take turns in the order (0,0), (1,0),
// (1,1), (0,1): one a frame over 4 frames, the diagonal pairs (a checkerboard) over 2. So any 2 x 2 window
// (the upsample's, a filter tap pair) holds a pixel traced this frame.
// The includer's push constants have traceFrames and tracePhase (frame index mod traceFrames).
#ifndef DYNGI_VCT_TRACE_PHASE_GLSL
#define DYNGI_VCT_TRACE_PHASE_GLSL

ivec2 vctLatticeOffset(uint k) {
  k &= 3u;
  return ivec2(k == 1u || k == 2u ? 1 : 0, k >= 2u ? 1 : 0);
}

// The traced pixel invocation `id` of the trace dispatch handles: the dispatch covers every pixel when
// traceFrames is 1, else the half-resolution lattice once per offset traced this frame (id.z).
ivec2 vctTracedPixel(uvec3 id) {
  if (traceFrames <= 1u) return ivec2(id.xy);
  return 2 * ivec2(id.xy) + vctLatticeOffset(tracePhase + id.z * traceFrames);
}

bool vctTracedThisFrame(ivec2 q) {
  if (traceFrames <= 1u) return true;
  uint k = q.y % 2 == 0 ? uint(q.x % 2) : 3u - uint(q.x % 2);
  return (k + 4u - tracePhase) % traceFrames == 0u;
}

#endif
