// The same relative-to-eye subtract, with every step precise: nothing to report.
#version 450

layout(location = 0) in vec3 positionHigh;
layout(location = 1) in vec3 positionLow;

layout(std140, binding = 0) uniform View {
  mat4 modelViewProjectionRelativeToEye;
  vec3 cameraHigh;
  vec3 cameraLow;
} view;

vec3 translateRelativeToEye(vec3 high, vec3 low) {
  precise vec3 highDifference = high - view.cameraHigh;
  precise vec3 lowDifference = low - view.cameraLow;
  precise vec3 offset = highDifference + lowDifference;
  return offset;
}

void main() {
  vec3 p = translateRelativeToEye(positionHigh, positionLow);
  gl_Position = view.modelViewProjectionRelativeToEye * vec4(p, 1.0);
}
