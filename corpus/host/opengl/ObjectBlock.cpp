// A per-object uniform block filled from a double model matrix (glm), with no camera in scope: the
// matrix goes up relative to its own origin, and the origin beside it.
#include <glm/glm.hpp>

#include "gl_mini.h"

struct ObjectBlock {
  glm::mat4 model;
  glm::vec4 tint;
};

struct SceneNode {
  glm::dmat4 modelMatrix;
  glm::dvec4 tint;
};

void UploadObject(ObjectBlock& block, const SceneNode& node)
{
  block.model = glm::mat4(node.modelMatrix);
  block.tint = glm::vec4(node.tint);
  glBufferSubData(GL_UNIFORM_BUFFER, 0, sizeof block, &block);
}
