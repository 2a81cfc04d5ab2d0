// The least a render kernel can be: one store a pixel, the bindings of the real kernels unused.
// Its pipeline creation is lavapipe's floor (measure.sh).
#version 450
layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, set = 0, binding = 0) buffer Pixels { vec4 px[]; };
void main() { px[gl_GlobalInvocationID.x] = vec4(1.0); }
