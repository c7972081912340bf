// A uniform block shared by several units: its struct is declared here, filled in SkySetup.cpp.
#pragma once
#include <glm/glm.hpp>

struct SkyUniforms {
  glm::vec3 sunPosition;
  float sunRadius;
  glm::vec3 moonDirection;
  float exposure;
};
