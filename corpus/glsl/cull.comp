// GPU frustum culling of object bounds stored in world space.
#version 450
layout(local_size_x = 64) in;

struct ObjectBounds {
  vec4 centerRadius;
};

layout(std430, binding = 0) readonly buffer Bounds { ObjectBounds bounds[]; };
layout(std430, binding = 1) writeonly buffer Visible { uint visible[]; };

uniform vec4 frustumPlanes[6];
uniform vec3 u_cameraPosition;
uniform float maxDistance;

void main() {
  uint i = gl_GlobalInvocationID.x;
  vec3 center = bounds[i].centerRadius.xyz;
  float radius = bounds[i].centerRadius.w;
  bool inside = distance(center, u_cameraPosition) - radius < maxDistance;
  for (int p = 0; p < 6; ++p) {
    inside = inside && dot(frustumPlanes[p].xyz, center) + frustumPlanes[p].w > -radius;
  }
  visible[i] = inside ? 1u : 0u;
}
