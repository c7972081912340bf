// Relative-to-eye rendering with high/low position pairs, written without precise.
#version 450

layout(location = 0) in vec3 positionHigh;
layout(location = 1) in vec3 positionLow;

layout(std140, binding = 0) uniform View {
  mat4 modelViewProjectionRelativeToEye;
  vec3 cameraHigh;
  vec3 cameraLow;
} view;

vec3 translateRelativeToEye(vec3 high, vec3 low) {
  vec3 highDifference = high - view.cameraHigh;
  vec3 lowDifference = low - view.cameraLow;
  return highDifference + lowDifference;
}

void main() {
  vec3 p = translateRelativeToEye(positionHigh, positionLow);
  gl_Position = view.modelViewProjectionRelativeToEye * vec4(p, 1.0);
}
