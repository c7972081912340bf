// The camera of a camera-relative renderer: the view looks from the origin, and the eye's world
// position goes apart. Nothing here is narrowed.
#include <glm/gtc/matrix_transform.hpp>

#include "FrameUniforms.h"

FrameUniforms make_frame(const glm::dvec3& eye, const glm::dvec3& forward, double aspect)
{
  FrameUniforms frame;
  frame.proj = glm::perspective(1.0, aspect, 0.1, 1.0e7);
  glm::dmat4 view = glm::lookAt(glm::dvec3(0.0, 0.0, 0.0), forward, glm::dvec3(0.0, 1.0, 0.0));
  frame.view = view;
  frame.cameraPosition = eye;
  return frame;
}

// A shadow pass looks from the origin as well.
FrameUniforms make_shadow_frame(const glm::dvec3& toSun)
{
  FrameUniforms frame;
  frame.proj = glm::ortho(-1.0e3, 1.0e3, -1.0e3, 1.0e3, -1.0e4, 1.0e4);
  frame.view = glm::lookAt(glm::dvec3(0.0), -toSun, glm::dvec3(0.0, 1.0, 0.0));
  return frame;
}

StarMapUniforms make_star_map(const glm::dmat4& orientation)
{
  StarMapUniforms stars;
  stars.view = orientation;
  return stars;
}
