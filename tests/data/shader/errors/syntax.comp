#version 460
layout(local_size_x = 1) in;
layout(std430, binding = 0) buffer Out { float result[]; };

void main() {
  result[0] = undeclaredThing;
}
