// The frame's draw records (gpu::DrawRecord per slot, then gpu::DrawMaterialRecord per material;
// render::FrameInstances), at the binding the including pass defines as DYNGI_DRAW_INSTANCES_BINDING:
// a vertex stage reads its instance's at gl_InstanceIndex. Both records are four vec4s, read as such.
#ifndef DYNGI_DRAW_INSTANCES_BINDING
#error "define DYNGI_DRAW_INSTANCES_BINDING (the pass's binding of the draw records) before including draw_instances.glsl"
#endif
layout(set = 0, binding = DYNGI_DRAW_INSTANCES_BINDING) readonly buffer DrawRecords { vec4 drawRecordWords[]; };

// A draw's transform and material constants, assembled from its records.
struct DrawInstance {
  mat4 model;
  vec4 baseColor;  // gpu::DrawMaterialRecord's fields
  vec4 emissive;
  vec4 params;
  vec4 uvLinear;
};

mat4 drawModel(uint slot) {
  return transpose(mat4(drawRecordWords[4u * slot], drawRecordWords[4u * slot + 1u], drawRecordWords[4u * slot + 2u], vec4(0.0, 0.0, 0.0, 1.0)));
}

DrawInstance drawInstance(uint slot) {
  DrawInstance d;
  d.model = drawModel(slot);
  const uint m = 4u * floatBitsToUint(drawRecordWords[4u * slot + 3u].x);
  d.baseColor = drawRecordWords[m];
  d.emissive = drawRecordWords[m + 1u];
  d.params = drawRecordWords[m + 2u];
  d.uvLinear = drawRecordWords[m + 3u];
  return d;
}
