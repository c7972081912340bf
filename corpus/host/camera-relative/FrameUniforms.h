// What a camera-relative renderer hands every draw: the camera sits at the origin of `view`, and its
// world position is kept apart, in double. Each draw's matrices are made relative to it.
#pragma once
#include <string>

#include <glm/glm.hpp>

#include "gl_mini.h"

struct FrameUniforms {
  glm::dmat4 proj;
  glm::dmat4 view;  // a rotation only: Camera.cpp looks from the origin
  glm::dvec3 cameraPosition;
};

// Where a star map draws from: a `view` this project gives nothing that says what it holds.
struct StarMapUniforms {
  glm::dmat4 view;
};

class Program {
 public:
  unsigned id = 0;
  void setMat4(const std::string& name, const glm::mat4& value) const { glUniformMatrix4fv(location(name), 1, GL_FALSE, &value[0][0]); }
  void setVec3(const std::string& name, const glm::vec3& value) const { glUniform3fv(location(name), 1, &value[0]); }

 private:
  int location(const std::string& name) const { return glGetUniformLocation(id, name.c_str()); }
};

FrameUniforms make_frame(const glm::dvec3& eye, const glm::dvec3& forward, double aspect);
StarMapUniforms make_star_map(const glm::dmat4& orientation);
