// The frame's draw records (gpu::DrawInstance, render::FrameInstances), at the binding the including
// pass defines as DYNGI_DRAW_INSTANCES_BINDING: a vertex stage reads its instance's at gl_InstanceIndex.
#ifndef DYNGI_DRAW_INSTANCES_BINDING
#error "define DYNGI_DRAW_INSTANCES_BINDING (the pass's binding of the draw records) before including draw_instances.glsl"
#endif
layout(set = 0, binding = DYNGI_DRAW_INSTANCES_BINDING) readonly buffer DrawInstances { DrawInstance drawInstances[]; };
