// The GI's output (an RGBA32F or RGBA16F target) into a host's image of format EXPORT_FORMAT, pixel for
// pixel; `zero` writes 0 (no specular light this frame).
#include "shared/gi_gpu_types.h"
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = DYNGI_EXPORT_BINDING_IN) uniform sampler2D source;
layout(set = 0, binding = DYNGI_EXPORT_BINDING_OUT, EXPORT_FORMAT) uniform writeonly image2D destination;
layout(push_constant) uniform Push { DYNGI_EXPORT_PUSH };
void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (px.x >= int(width) || px.y >= int(height)) return;
  imageStore(destination, px, zero == 1u ? vec4(0.0) : texelFetch(source, px, 0));
}
