#version 300 es
// three.js-style forward fragment shader: view vector from absolute world positions.
precision highp float;

uniform vec3 cameraPosition;
uniform vec3 lightDirection;
uniform vec3 diffuse;

in vec3 vTranslatedWorldPosition;
in vec3 vNormal;

out vec4 fragColor;

void main() {
  vec3 viewDir = normalize(-vTranslatedWorldPosition);
  vec3 n = normalize(vNormal);
  float lambert = max(dot(n, -lightDirection), 0.0);
  float rim = pow(1.0 - max(dot(n, viewDir), 0.0), 3.0);
  fragColor = vec4(diffuse * lambert + rim, 1.0);
}
