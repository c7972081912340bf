#version 300 es
// A globe engine's relative-to-eye vertex shader (WebGL 2): positions arrive as high/low pairs,
// the eye as a pair too, and the view matrix is used for its rotation only. Nothing here holds an
// absolute position that float32 rounding can reach: the view matrix (rotation only), the sun
// (a direction), the point normalised from the globe's centre and the view vector (a difference)
// are not reported. The high/low sums are, and GLSL ES 3.00 has no `precise` to offer for them.
precision highp float;

uniform mat4 viewMatrix;
uniform mat4 projectionMatrix;
uniform vec3 eyePositionHigh;
uniform vec3 eyePositionLow;
uniform vec3 cameraPosition;
uniform vec3 lightPosition;

in vec3 aPositionHigh;
in vec3 aPositionLow;
in vec3 aNormal;

out vec3 vLightDirection;
out vec3 vViewVec;
out float vShade;

void main() {
    // The view matrix with its translation cleared: a rotation for eye-relative offsets.
    mat4 viewMatrixRTE = viewMatrix;
    viewMatrixRTE[3] = vec4(0.0, 0.0, 0.0, 1.0);
    mat4 m = projectionMatrix * viewMatrixRTE;

    vec3 highDiff = aPositionHigh - eyePositionHigh;
    vec3 lowDiff = aPositionLow - eyePositionLow;
    // An absolute point only used for its direction from the globe's centre.
    vec3 worldPosition = highDiff + lowDiff + cameraPosition;
    vec3 up = normalize(worldPosition);
    vShade = dot(up, aNormal);

    // The sun: far away, only ever a direction.
    vLightDirection = normalize(lightPosition);
    // A view vector: a difference of two positions.
    vec3 pos = highDiff + lowDiff;
    vViewVec = cameraPosition - pos;

    gl_Position = m * vec4(highDiff + lowDiff, 1.0);
}
