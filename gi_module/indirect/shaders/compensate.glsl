// The clamp compensation's low-resolution layout, shared by compensate.comp (which traces it) and
// filter_columns.comp (which adds it): texel q stands for the pixel near the middle of its
// DYNGI_COMPENSATE_SCALE^2 block. Needs FrameUniforms `frame` declared before inclusion.
ivec2 compensationSize() { return (ivec2(frame.sizeAndCount.xy) + DYNGI_COMPENSATE_SCALE - 1) / DYNGI_COMPENSATE_SCALE; }
ivec2 tracedPixel(ivec2 q) {
  return min(q * DYNGI_COMPENSATE_SCALE + DYNGI_COMPENSATE_SCALE / 2, ivec2(frame.sizeAndCount.xy) - 1);
}
