// Templates whose patterns hold world-space names with types the template's arguments decide:
// lwcport-host reads the instantiations (where the types are known) and must cope with the
// patterns, whose expressions have dependent types or none at all (a parenthesised initialiser).
#include <utility>

#include <glm/glm.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "gl_mini.h"

// A constructor initialiser from a member of a dependent argument (no type until instantiated).
template <typename T>
struct Cursor {
  T location;
  T worldPosition;
  template <typename R>
  Cursor(const R& rhs) : location(rhs.location), worldPosition(rhs.worldPosition) {}
  template <typename R>
  Cursor(const R& a, const R& b) : location(a.location - b.location), worldPosition{a.worldPosition} {}
};

// Assignments to members of dependent type, and the dependent `this->`.
template <typename Vec>
struct Transform {
  Vec worldPosition;
  Vec cameraPosition;
  glm::vec3 uploaded;
  void Set(const Vec& p) { this->worldPosition = p; }
  template <typename Other>
  void CopyFrom(const Other& other) {
    worldPosition = other.worldPosition;
    cameraPosition = Vec(other.cameraPosition);
    uploaded = glm::vec3(other.worldPosition - other.cameraPosition);
  }
};

// Uploads whose arguments depend on the template's parameter: casts, functional casts, calls.
template <typename V>
void UploadPosition(GLint at, const V& worldPosition) {
  glUniform3f(at, (float)worldPosition.x, static_cast<float>(worldPosition.y), float(worldPosition.z));
}

template <typename V>
void UploadOffset(GLint at, const V& worldPosition, const V& eye) {
  glUniform3fv(at, 1, glm::value_ptr(glm::vec3(worldPosition - eye)));
}

// A split whose halves' type is the template's.
template <typename T, typename D>
void Split(D value, T& high, T& low) {
  high = T(value);
  low = T(value - D(high));
}

// Variadic and generic code: fold expressions, parameter packs, generic lambdas.
template <typename... P>
float SumAll(P... parts) { return (float(parts) + ... + 0.0f); }

template <typename M>
auto Apply(const M& worldMatrix) {
  auto narrow = [](const auto& m) { return glm::mat4(m); };
  return narrow(worldMatrix);
}

template <typename T>
struct Box {
  T worldPosition;
  Box(T p) : worldPosition(std::move(p)) {}
  auto Narrowed() const -> decltype(glm::vec3(worldPosition)) { return glm::vec3(worldPosition); }
};

// A template no one instantiates: only its pattern exists.
template <typename T>
void NeverUsed(GLint at, T worldPosition, T cameraPosition) {
  T relative(worldPosition.x - cameraPosition.x, worldPosition.y - cameraPosition.y, worldPosition.z - cameraPosition.z);
  glUniform3f(at, (float)relative.x, (float)relative.y, (float)relative.z);
  Cursor<T> copy(relative, relative);
  (void)copy;
}

struct Body {
  glm::dvec3 location;
  glm::dvec3 worldPosition;
  glm::dvec3 cameraPosition;
};

void Instantiate(GLint at, const Body& body) {
  Cursor<glm::dvec3> cursor(body);
  Transform<glm::dvec3> transform;
  transform.Set(body.worldPosition);
  transform.CopyFrom(body);
  UploadOffset(at, body.worldPosition, body.cameraPosition);
  UploadPosition(at, body.worldPosition);  // a world position narrowed: found in the instantiation
  UploadPosition(at + 1, body.location);
  glm::vec3 high, low;
  Split(body.worldPosition, high, low);
  (void)SumAll(1.0, 2.0f, 3);
  glm::dmat4 identity(1.0);
  (void)Apply(identity);
  (void)cursor;
}
