// A small OpenGL scene renderer on glm, with positions kept in double on the CPU. The .lwcport.json
// beside it names the camera origin (`Camera::position`) that translated fixes subtract.
#include <glm/glm.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <vector>

#include "gl_mini.h"

struct SceneNode {
  glm::dvec3 position;
  glm::dmat4 modelMatrix;
  glm::dvec3 lightDirection;
};

struct Camera {
  glm::dvec3 position;
  glm::dmat4 view;
  glm::dmat4 projection;
};

struct SceneUniforms {
  glm::vec3 cameraPosition;
  float time;
  glm::mat4 viewProjection;
};

struct Locations {
  GLint nodePosition, camera, model, modelView, light;
};

void DrawNode(const SceneNode& node, const Camera& camera, const Locations& at)
{
  glUniform3fv(at.nodePosition, 1, glm::value_ptr(glm::vec3(node.position)));
  glUniform3f(at.camera, (float)camera.position.x, (float)camera.position.y, (float)camera.position.z);
  glUniform3f(at.nodePosition, (float)node.position.x, (float)node.position.y, (float)node.position.z);
  glUniformMatrix4fv(at.model, 1, GL_FALSE, glm::value_ptr(glm::mat4(node.modelMatrix)));
  // Right: the model-view product is computed in double, where the two translations cancel.
  glUniformMatrix4fv(at.modelView, 1, GL_FALSE, glm::value_ptr(glm::mat4(camera.view * node.modelMatrix)));
  // Right: relative to the eye, in double.
  glUniform3fv(at.nodePosition, 1, glm::value_ptr(glm::vec3(node.position - camera.position)));
  // A direction is not a position.
  glUniform3fv(at.light, 1, glm::value_ptr(glm::vec3(node.lightDirection)));
  // The node's anchor, taken into the world by its model matrix in double: a world position.
  const glm::dvec3 anchor = glm::dvec3(node.modelMatrix * glm::dvec4(0.0, 0.0, 10.0, 1.0));
  glUniform3fv(at.nodePosition, 1, glm::value_ptr(glm::vec3(anchor)));
  // The light's axis, taken into the world: a direction (w = 0) whatever it is called.
  const glm::dvec3 lightPosition = glm::dvec3(node.modelMatrix * glm::dvec4(0.0, 0.0, 1.0, 0.0));
  glUniform3fv(at.light, 1, glm::value_ptr(glm::vec3(lightPosition)));
}

void FillUniforms(SceneUniforms& uniforms, const Camera& camera, float time)
{
  uniforms.cameraPosition = glm::vec3(camera.position);
  uniforms.time = time;
  uniforms.viewProjection = glm::mat4(camera.projection * camera.view);
}

// 28 bytes: a member added at the end would not sit where the shader's block puts it.
struct LightUniforms {
  glm::vec3 lightPosition;
  float intensity;
  glm::vec3 color;
};

void FillLight(LightUniforms& light, const SceneNode& node)
{
  light.lightPosition = glm::vec3(node.position);
}

// A vertex buffer of orbit points: the array handed to glBufferData is GPU data, whatever its name.
struct TrailPoint {
  float x, y, z;
  float time;
};

void FillTrail(std::vector<TrailPoint>& points, const std::vector<glm::dvec3>& orbitPositions)
{
  for (size_t i = 0; i < orbitPositions.size(); ++i) {
    const glm::dvec3 position = orbitPositions[i];
    points[i].x = static_cast<float>(position.x);
  }
  glBufferData(GL_ARRAY_BUFFER, static_cast<long>(points.size() * sizeof(TrailPoint)), points.data(), GL_STATIC_DRAW);
}

// Orbit points with their time in double: 24 bytes, a vertex layout (its stride is given as
// `sizeof`), so a member added at the end needs no 16-byte row, only an attribute of its own.
struct OrbitVertex {
  float x, y, z;
  double time;
};

void FillOrbit(std::vector<OrbitVertex>& vertices, const std::vector<glm::dvec3>& positions, unsigned vertexArray, unsigned buffer)
{
  glVertexArrayVertexBuffer(vertexArray, 0, buffer, 0, sizeof(OrbitVertex));
  for (size_t i = 0; i < positions.size(); ++i) {
    const glm::dvec3 position = positions[i];
    vertices[i].x = static_cast<float>(position.x);
  }
  glNamedBufferData(buffer, static_cast<long>(vertices.size() * sizeof(OrbitVertex)), vertices.data(), GL_STATIC_DRAW);
}
