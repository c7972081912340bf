// The seed renderer's design: rotation/scale as mat3, translations as high/low pairs.
#version 450

layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;

uniform mat3 u_modelRotationScale;
uniform vec3 u_modelTranslationHigh;
uniform vec3 u_modelTranslationLow;
uniform vec3 u_cameraTranslationHigh;
uniform vec3 u_cameraTranslationLow;
uniform mat4 u_viewRotationProjection;

out vec3 vNormal;

void main() {
  precise vec3 highPart = u_modelTranslationHigh - u_cameraTranslationHigh;
  precise vec3 lowPart = u_modelTranslationLow - u_cameraTranslationLow;
  precise vec3 objectOffset = highPart + lowPart;
  vec3 cameraRelative = u_modelRotationScale * position + objectOffset;
  vNormal = normalize(u_modelRotationScale * normal);
  gl_Position = u_viewRotationProjection * vec4(cameraRelative, 1.0);
}
