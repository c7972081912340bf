#version 300 es
#extension GL_GOOGLE_include_directive : require
// three.js-style forward vertex shader: world position computed on the GPU in float32.
precision highp float;

#include "lwc_doublefloat.glsl"
uniform FDFVector3 cameraTranslation;
uniform mat3 modelRotationScale;
uniform FDFVector3 modelTranslation;
uniform mat4 translatedViewMatrix;
uniform mat4 projectionMatrix;
uniform mat3 normalMatrix;

in vec3 position;
in vec3 normal;

out vec3 vTranslatedWorldPosition;
out vec3 vNormal;

void main() {
  vec4 translatedWorldPosition = vec4(modelRotationScale * position + DFFastLocalSubtractDemote(modelTranslation, cameraTranslation), 1.0);
  vTranslatedWorldPosition = translatedWorldPosition.xyz;
  vNormal = normalize(normalMatrix * normal);
  gl_Position = projectionMatrix * translatedViewMatrix * translatedWorldPosition;
}
