#version 300 es
// A globe's fragment shader whose world values go through included helpers: the sun position is
// only ever normalised there (a direction: not reported), the eye position meets a surface point
// in a distance there (its float32 rounding reaches the fog: reported).
#extension GL_GOOGLE_include_directive : require
precision highp float;

#include "lighting.glsl"

uniform vec3 lightPosition;
uniform vec3 cameraPosition;
uniform vec3 albedo;

in vec3 vNormal;
in vec3 vSurface;
out vec4 fragColor;

// Set once per invocation and read by the helpers below.
vec3 sunPos;

vec3 shade(vec3 normal)
{
	return phong(normal, sunPos, vec3(0.0, 0.0, 1.0), albedo);
}

void main()
{
	sunPos = lightPosition;
	vec3 color = shade(normalize(vNormal));
	float fog = fogAmount(cameraPosition, vSurface, 1e-5);
	fragColor = vec4(mix(color, vec3(0.7), fog), 1.0);
}
