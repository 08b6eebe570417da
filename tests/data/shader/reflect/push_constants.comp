#version 460
// vec4 + uint + float: 16 + 4 + 4 = 24 bytes.
layout(local_size_x = 16, local_size_y = 16) in;
layout(push_constant) uniform Push { vec4 tint; uint frame; float exposure; } pc;
layout(set = 0, binding = 0, rgba16f) uniform writeonly image2D outImage;

void main() { imageStore(outImage, ivec2(gl_GlobalInvocationID.xy), pc.tint * pc.exposure * float(pc.frame)); }
