// Local-space and clip-space math: the model-view matrix is computed in double on the host.
#version 450

layout(location = 0) in vec3 position;
layout(location = 1) in vec2 uv;

uniform mat4 modelViewMatrix;
uniform mat4 projectionMatrix;
uniform float time;

out vec2 vUv;
out float vDepth;

void main() {
  vec3 displaced = position + vec3(0.0, sin(position.x * 4.0 + time) * 0.1, 0.0);
  vec4 viewPosition = modelViewMatrix * vec4(displaced, 1.0);
  vUv = uv;
  vDepth = -viewPosition.z;
  gl_Position = projectionMatrix * viewPosition;
}
