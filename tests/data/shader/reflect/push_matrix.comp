#version 460
// mat4 (64) + vec2 at 64 (8) + float[3] at 72 (stride 4, 12): 84 bytes.
layout(local_size_x = 64) in;
layout(push_constant, std430) uniform Push { mat4 transform; vec2 offset; float weights[3]; } pc;
layout(std430, binding = 0) buffer Out { vec4 result[]; };

void main() {
  result[gl_GlobalInvocationID.x] = pc.transform * vec4(pc.offset, pc.weights[0] + pc.weights[2], 1.0);
}
