#version 300 es
// The model matrix only turns normals here (w = 0): its translation never acts, so its float32
// rounding reaches no result. Positions are projected by one matrix the host composed.
precision highp float;

uniform mat4 modelMatrix;
uniform mat4 modelViewProjectionMatrix;

in vec3 position;
in vec3 normal;
out vec3 vNormal;

void main()
{
	vNormal = normalize((modelMatrix * vec4(normal, 0.0)).xyz);
	gl_Position = modelViewProjectionMatrix * vec4(position, 1.0);
}
