#version 460
// local_size_x through a specialization constant with default 32: for SPIR-V 1.6 glslang
// writes OpExecutionModeId LocalSizeId pointing at OpSpecConstant / OpConstant.
layout(local_size_x_id = 0, local_size_x = 32, local_size_y = 2, local_size_z = 1) in;
layout(std430, binding = 0) buffer Out { uint result[]; };

void main() { result[gl_GlobalInvocationID.x] = gl_WorkGroupSize.x; }
