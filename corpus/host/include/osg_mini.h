// A few OpenSceneGraph-like declarations, written for lwcport's corpus: vectors with a conversion
// operator from double to float, and uniforms (not OpenSceneGraph's code).
#pragma once
namespace osg {
struct Vec2f {
  float _v[2];
  Vec2f(float x, float y) : _v{x, y} {}
};
struct Vec2d {
  double _v[2];
  Vec2d(double x, double y) : _v{x, y} {}
  operator Vec2f() const { return Vec2f(float(_v[0]), float(_v[1])); }
  Vec2d operator-(const Vec2f& o) const { return Vec2d(_v[0] - o._v[0], _v[1] - o._v[1]); }
};
struct Vec3f {
  float _v[3];
  Vec3f(float x, float y, float z) : _v{x, y, z} {}
};
struct Vec3d {
  double _v[3];
  Vec3d(double x, double y, double z) : _v{x, y, z} {}
  // As in OpenSceneGraph: a double vector converts to a float one implicitly.
  operator Vec3f() const { return Vec3f(float(_v[0]), float(_v[1]), float(_v[2])); }
  Vec3d operator-(const Vec3d& o) const { return Vec3d(_v[0] - o._v[0], _v[1] - o._v[1], _v[2] - o._v[2]); }
  double normalize();  // to unit length, in place; returns the old length
};
struct Uniform {
  Uniform(const char* name, const Vec3f& value);
  bool set(const Vec3f& value);
};
struct StateSet {
  void addUniform(Uniform* uniform);
};
}  // namespace osg
