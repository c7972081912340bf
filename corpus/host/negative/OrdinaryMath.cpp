// Host code lwcport must leave alone: float math that never held a world position, directions,
// local-space data, templates, lambdas, and uploads that are already camera-relative or split.
#include <cmath>

#include <glm/glm.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "gl_mini.h"

double Compute();
float Scale(double factor) { return (float)factor; }

struct MaterialConstants {
  glm::vec3 baseColor;
  float roughness;
  glm::vec3 lightDirection;
  glm::vec3 eyeHigh;
  glm::vec3 eyeLow;
};

template <typename T>
T Lerp(T a, T b, double t) { return T(a + (b - a) * t); }

void FillMaterial(MaterialConstants& constants, const glm::dvec3& sunDirection, double roughness, const glm::dvec3& eye)
{
  constants.roughness = (float)Compute();
  constants.roughness = static_cast<float>(roughness);
  constants.lightDirection = glm::vec3(glm::normalize(sunDirection));
  constants.baseColor = glm::vec3(Lerp(glm::dvec3(1.0), glm::dvec3(0.5), 0.25));
  // The eye as a high/low pair, split in double: right.
  glm::vec3 eyeHi = glm::vec3(eye);
  constants.eyeHigh = eyeHi;
  constants.eyeLow = glm::vec3(eye - glm::dvec3(eyeHi));
  auto upload = [&](GLint at, const glm::dvec3& offsetFromEye) { glUniform3fv(at, 1, glm::value_ptr(glm::vec3(offsetFromEye))); };
  upload(0, glm::dvec3(1.0, 2.0, 3.0));
}

void DrawLocal(const glm::dmat4& localMatrix, const glm::dvec3& localPosition, GLint at)
{
  glUniformMatrix4fv(at, 1, GL_FALSE, glm::value_ptr(glm::mat4(localMatrix)));
  glUniform3f(at, (float)localPosition.x, (float)localPosition.y, (float)localPosition.z);
  float length = (float)glm::length(localPosition);
  glUniform3f(at, length, Scale(2.0), 0.0f);
}

// The eye moved, in double, into a globe's own frame before it is narrowed: a position in the
// globe's frame, whatever its name says (the globe's transform is no world matrix the tables know).
void DrawGlobe(const glm::dmat4& globeTransform, const glm::dmat4& viewMatrix, const glm::dvec3& eyeInWorld, GLint at)
{
  const glm::dvec3 cameraPosition = glm::dvec3(glm::inverse(globeTransform) * glm::dvec4(eyeInWorld, 1.0));
  glUniform3fv(at, 1, glm::value_ptr(glm::vec3(cameraPosition)));
  // A world point taken into view space: camera-relative.
  const glm::dvec4 eyePosition = viewMatrix * glm::dvec4(eyeInWorld, 1.0);
  glUniform3fv(at, 1, glm::value_ptr(glm::vec3(eyePosition)));
}

// glm's matrices act on column vectors, so the right factor acts first: a matrix the tables do not
// know, then the view. It hands the view world positions, so it is a model matrix and the product
// is camera-relative.
void DrawPlaced(const glm::dmat4& viewMatrix, const glm::dmat4& placement, GLint at)
{
  glUniformMatrix4fv(at, 1, GL_FALSE, glm::value_ptr(glm::mat4(viewMatrix * placement)));
}

// A lone number named as a position: the scroll wheel's, not a point in the world.
struct InputState {
  float wheel;
};

void OnScroll(InputState& input, double position)
{
  input.wheel = static_cast<float>(position);
}

// Two numbers named as a position: a cursor's place on the screen, not a point in a 3D world.
void DrawCursor(const glm::dvec2& pos, GLint at)
{
  glUniform2fv(at, 1, glm::value_ptr(glm::vec2(pos)));
}

// A record named as a position that is no vector: a GPS fix, whose speed is no coordinate.
struct GpsFix {
  double latitudeDeg, longitudeDeg, altitude;
  int satellites;
  double speedKnots;
};
struct TelemetryPacket {
  float airspeed;
};

void Relay(TelemetryPacket& packet, const GpsFix& pos)
{
  packet.airspeed = pos.speedKnots;
}

// A world position minus a point the tables do not know: relative to that point.
void DrawFromAnchor(const glm::dvec3& worldPosition, const glm::dvec3& anchor, GLint at)
{
  glUniform3fv(at, 1, glm::value_ptr(glm::vec3(worldPosition - anchor)));
}

// A game object reached by a pointer named as a position: a record of many kinds of member, not a
// vector, so its coordinates are not judged by that name.
struct GameObject {
  unsigned id;
  int type;
  double x, y, z;
};
struct Beam {
  float fromX, fromY, fromZ;
};

void AimBeam(Beam& beam, const GameObject* origin)
{
  beam.fromX = origin->x;
  beam.fromY = origin->y;
  beam.fromZ = origin->z;
}

// A point held in float from the start, made double only by `cos` and `sin` on the way: its
// narrowing back rounds nothing that was not in float already.
struct Vec3f {
  float x, y, z;
};

void PointOnRing(const Vec3f* center, float radius, double angle, Vec3f* point)
{
  point->x = center->x + radius * std::cos(angle);
  point->y = center->y + radius * std::sin(angle);
  point->z = center->z;
}
