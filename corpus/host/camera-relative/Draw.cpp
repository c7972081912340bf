// The draws of a camera-relative renderer. Its `view` holds a rotation only, which this unit cannot
// see, but Camera.cpp, in the same run, shows: narrowing it rounds no world translation.
#include <glm/gtc/matrix_transform.hpp>

#include "FrameUniforms.h"

void DrawPlanet(const Program& program, const FrameUniforms& frame, const glm::dvec3& planetCenter, double radius)
{
  program.setMat4("view", glm::mat4(frame.view));
  program.setMat4("projView", glm::mat4(frame.proj * frame.view));
  // The planet's model matrix, relative to the camera, in double first: nothing large goes up.
  glm::dmat4 model = glm::translate(glm::dmat4(1.0), planetCenter - frame.cameraPosition);
  program.setMat4("model", glm::mat4(glm::scale(model, glm::dvec3(radius))));
}

// A view made here, from the origin: its name says world-to-view, its value says rotation only.
void DrawSkyDome(const Program& program, const glm::dvec3& forward)
{
  glm::dmat4 view = glm::lookAt(glm::dvec3(0.0), forward, glm::dvec3(0.0, 0.0, 1.0));
  program.setMat4("view", glm::mat4(view));
}

// Positives. The eye's world position goes up in float, and a view made from it keeps its
// translation (millions of metres out).
void DrawMarker(const Program& program, const FrameUniforms& frame, const glm::dvec3& target)
{
  program.setVec3("eye", glm::vec3(frame.cameraPosition));
  program.setMat4("markerView", glm::mat4(glm::lookAt(frame.cameraPosition, target, glm::dvec3(0.0, 0.0, 1.0))));
}

// A star map's `view`: the project gives it only a matrix it does not know, so its name is trusted.
void DrawStars(const Program& program, const StarMapUniforms& stars)
{
  program.setMat4("view", glm::mat4(stars.view));
}
