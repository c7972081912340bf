// The high/low fix for a member declared in a header of the project: the low half is declared
// there, beside the high one, and filled here (one fix, two files).
#include <glm/glm.hpp>

#include "SkyUniforms.h"

struct Body {
  glm::dvec3 position;
  double radius;
};

void FillSky(SkyUniforms& sky, const Body& sun, const glm::dvec3& moonDirection)
{
  sky.sunPosition = glm::vec3(sun.position);
  sky.sunRadius = static_cast<float>(sun.radius);
  sky.moonDirection = glm::vec3(moonDirection);
}
