// A program assembled in a script: the vertex stage writes a constant into a varying named like a
// camera position (a test stub's), and the fragment stage reads it. Neither holds a world position.
export const vs = `#version 300 es
precision highp float;
in vec3 positions;
out vec3 cameraPosition;
void main() {
  cameraPosition = vec3(1.0);
  gl_Position = vec4(positions, 1.0);
}
`;

export const fs = `#version 300 es
precision highp float;
in vec3 cameraPosition;
out vec4 fragColor;
void main() {
  fragColor = vec4(cameraPosition, 1.0);
}
`;
