// The uniforms a scene-graph renderer sets for a node from the node's double transform. Its world
// position and its local-to-world matrix go to the GPU in float; so does a camera node's.
#include "scene_mini.h"

using namespace scene;

struct NodeUniforms {
  ptr<Uniform3f> worldPos, worldDir, cameraOffset;
  ptr<UniformMatrix4f> localToWorld, cameraToWorld, localToCamera;
};

// Positives.
void set_node_uniforms(const NodeUniforms& u, const SceneNode& node, const SceneNode& camera)
{
  u.worldPos->set(node.getWorldPos().cast<float>());
  u.localToWorld->setMatrix(node.getLocalToWorld().cast<float>());
  mat4d cameraToWorld = camera.getLocalToWorld();
  u.cameraToWorld->setMatrix(cameraToWorld.cast<float>());
}

// Negatives. The node's axis is a direction: the uniform it goes to says so, even where nothing
// in this unit shows the axis constant is one.
void set_node_axis(const NodeUniforms& u, const SceneNode& node)
{
  vec4d d = node.getLocalToWorld() * vec4d::UNIT_Z;
  u.worldDir->set(vec3f(float(d.x), float(d.y), float(d.z)));
}

// The node seen from the camera, composed in double: relative, and named so.
void set_camera_relative(const NodeUniforms& u, const SceneNode& node, const SceneNode& camera)
{
  u.cameraOffset->set((node.getWorldPos() - camera.getWorldPos()).cast<float>());
  u.localToCamera->setMatrix((camera.getWorldToLocal() * node.getLocalToWorld()).cast<float>());
}
