// A small orbit viewer drawn through a tutorial-style shader class (`setMat4`, `setVec3`): bodies
// keep their positions in double, the shader class takes floats.
#include <string>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "gl_mini.h"

class Shader {
 public:
  unsigned id = 0;
  void setMat4(const std::string& name, const glm::mat4& value) const { glUniformMatrix4fv(location(name), 1, GL_FALSE, &value[0][0]); }
  void setVec3(const std::string& name, const glm::vec3& value) const { glUniform3fv(location(name), 1, &value[0]); }
  void setFloat(const std::string& name, float value) const { glUniform1f(location(name), value); }

 private:
  int location(const std::string& name) const { return glGetUniformLocation(id, name.c_str()); }
};

// The body's model matrix carries its position, thousands of kilometres out, into a float matrix.
void DrawBody(const Shader& shader, const glm::dvec3& position, double radius)
{
  glm::dmat4 model = glm::translate(glm::dmat4(1.0), position);
  model = glm::scale(model, glm::dvec3(radius));
  shader.setMat4("model", glm::mat4(model));
  shader.setVec3("bodyCenter", glm::vec3(position));
}

// A constant position is still rounded where float cannot hold it (149,597,870.7 km).
void DrawSun(const Shader& shader)
{
  const glm::dvec3 position(0.0, -3185.5, 149597870.7);
  shader.setVec3("sunPosition", glm::vec3(position));
}

// A part scaled in its own frame, then placed in the world: the world translation goes up in float.
// After the model matrix, a matrix the tables do not know may be the camera's (here it is), which
// cancels the translation: that product is not reported.
void DrawPart(const Shader& shader, const glm::dmat4& cameraTransform, const glm::dmat4& model)
{
  shader.setMat4("model", glm::mat4(model * glm::scale(glm::dmat4(1.0), glm::dvec3(2.0))));
  shader.setMat4("partToCamera", glm::mat4(cameraTransform * model));
}

// Negatives. An overlay's centre in pixels, made of constants float holds exactly: nothing rounds.
void DrawAxesOverlay(int location)
{
  const int width = 64;
  const int margin = 8;
  const glm::dvec3 center(margin + width / 2, margin + width / 2, 0.0);
  glUniform3f(location, center.x, center.y, center.z);
}

// The sky box keeps the view's rotation only: the parameter named `view` is given a
// matrix without its translation before it goes up.
void DrawSky(const Shader& shader, glm::dmat4& view)
{
  view = glm::mat4(glm::mat3(view));
  shader.setMat4("view", glm::mat4(view));
}

// A rotation taken out of a world matrix has no translation to round.
void DrawAxes(const Shader& shader, const glm::dmat4& worldMatrix)
{
  shader.setMat4("axes", glm::mat4(glm::mat3(worldMatrix)));
}

// A position made relative to the eye before it goes up, under its own name.
void DrawMarker(const Shader& shader, glm::dvec3 pos, const glm::dvec3& eye)
{
  pos = pos - eye;
  shader.setVec3("marker", glm::vec3(pos));
  shader.setFloat("markerSize", float(glm::length(pos)));
}

// A class that only shares the setter's name uploads nothing.
struct Particle {
  glm::vec3 value;
  void setVec3(const std::string&, const glm::vec3& v) { value = v; }
};

void PlaceParticle(Particle& particle, const glm::dvec3& position)
{
  particle.setVec3("position", glm::vec3(position));
}
