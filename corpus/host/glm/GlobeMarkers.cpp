// Markers on a globe: a geodetic point made Cartesian is an Earth-centred position (6,378 km
// out), and the east-north-up frame at it carries that position as its translation.
#include <glm/glm.hpp>

struct Cartographic {
  double longitude, latitude, height;  // radians, radians, metres
};

struct Ellipsoid {
  glm::dvec3 cartographicToCartesian(const Cartographic& point) const;
};

struct Transforms {
  static glm::dmat4 eastNorthUpToFixedFrame(const glm::dvec3& origin);
};

struct MarkerProgram {
  void setVec3(const char* name, const glm::vec3& value) const;
  void setMat4(const char* name, const glm::mat4& value) const;
};

// Positives: rounded to half a metre at the Earth's radius.
void draw_marker(const MarkerProgram& program, const Ellipsoid& earth, const Cartographic& where)
{
  program.setVec3("markerCentre", glm::vec3(earth.cartographicToCartesian(where)));
  program.setMat4("markerFrame", glm::mat4(Transforms::eastNorthUpToFixedFrame(earth.cartographicToCartesian(where))));
}

// Negative: relative to the eye, in double, before it is narrowed.
void draw_marker_from(const MarkerProgram& program, const Ellipsoid& earth, const Cartographic& where, const glm::dvec3& eye)
{
  program.setVec3("markerCentre", glm::vec3(earth.cartographicToCartesian(where) - eye));
}
