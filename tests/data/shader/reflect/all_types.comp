#version 460
// One of every descriptor type the reflection must recognise, with arrays, 2D/3D and formats.
layout(local_size_x = 8, local_size_y = 4, local_size_z = 1) in;

layout(std140, set = 0, binding = 0) uniform Params { vec4 scale; uint count; } params;
layout(std430, set = 0, binding = 1) buffer Values { float data[]; } values;
layout(set = 0, binding = 2) uniform sampler2D colorTex;
layout(set = 0, binding = 3) uniform sampler3D noiseTex;
layout(set = 0, binding = 4, rgba16f) uniform image2D outImage;
layout(set = 0, binding = 5, r32f) uniform readonly image3D densityImage;

layout(set = 1, binding = 0) uniform texture2D separateTex;
layout(set = 1, binding = 1) uniform sampler linearSampler;
layout(set = 1, binding = 2) uniform texture3D volumes[3];
layout(set = 1, binding = 3, rgba32f) uniform image2D layers[2];

layout(set = 2, binding = 0, rgba8) uniform writeonly image2D ldrOut;
layout(set = 2, binding = 1, r8) uniform image2D mask;
layout(set = 2, binding = 2, r16f) uniform image2D halfImage;
layout(set = 2, binding = 3) uniform writeonly image2D noFormat;
layout(std430, set = 2, binding = 4) readonly buffer AnonBlock { uint anonymousData[]; };
layout(set = 2, binding = 5) uniform sampler2D textures[4];

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  vec2 uv = vec2(p) / 64.0;
  vec4 c = texture(colorTex, uv) + textureLod(noiseTex, vec3(uv, 0.5), 0.0);
  c += texture(sampler2D(separateTex, linearSampler), uv);
  c += texture(sampler3D(volumes[2], linearSampler), vec3(uv, 0.0));
  c += imageLoad(layers[1], p) + imageLoad(densityImage, ivec3(p, 0)).rrrr;
  c += imageLoad(mask, p) + imageLoad(halfImage, p) + texture(textures[3], uv);
  c *= params.scale * float(params.count + anonymousData[0]);
  values.data[p.x] = c.x;
  imageStore(outImage, p, c);
  imageStore(ldrOut, p, c);
  imageStore(noFormat, p, c);
}
