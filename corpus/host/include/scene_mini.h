// A small scene-graph library in the style of several research renderers, written for lwcport's
// corpus: vector and matrix templates with a `cast<U>()` conversion, uniforms typed by their value,
// and scene nodes that give their world transform in double.
#pragma once
namespace scene {

template <class T>
struct vec3 {
  T x, y, z;
  vec3() : x(0), y(0), z(0) {}
  vec3(T x, T y, T z) : x(x), y(y), z(z) {}
  template <class U>
  vec3<U> cast() const { return vec3<U>(U(x), U(y), U(z)); }
  vec3 operator-(const vec3& o) const { return vec3(x - o.x, y - o.y, z - o.z); }
};
template <class T>
struct vec4 {
  T x, y, z, w;
  vec4(T x, T y, T z, T w) : x(x), y(y), z(z), w(w) {}
  static const vec4 UNIT_Z;  // (0, 0, 1, 0), defined with the library
};
template <class T>
struct mat4 {
  T m[4][4];
  template <class U>
  mat4<U> cast() const;
  mat4 operator*(const mat4& o) const;
  vec4<T> operator*(const vec4<T>& v) const;
  mat4 inverse() const;
};
using vec3f = vec3<float>;
using vec3d = vec3<double>;
using vec4d = vec4<double>;
using mat4f = mat4<float>;
using mat4d = mat4<double>;

template <class T>
struct ptr {
  T* p;
  T* operator->() const { return p; }
};

class Uniform3f {
 public:
  void set(const vec3f& value);
};
class UniformMatrix4f {
 public:
  void setMatrix(const mat4f& value);
};

class SceneNode {
 public:
  mat4d getLocalToWorld() const;
  mat4d getWorldToLocal() const;
  vec3d getWorldPos() const;
};

}  // namespace scene
