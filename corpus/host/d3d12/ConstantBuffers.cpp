// A D3D12-style per-object constant buffer filled from scene objects kept in double (plain
// structs stand in for DirectXMath's; the upload is a copy into the mapped buffer).
#include <cstring>

struct float3 { float x, y, z; };
struct float4x4 { float m[4][4]; };
struct double3 { double x, y, z; };
struct double4x4 { double m[4][4]; };

struct ObjectConstants {
  float4x4 World;
  float3 WorldPosition;
  float Radius;
  float3 PositionHigh;
  float3 PositionLow;
};

struct SceneObject {
  double3 position;
  double4x4 worldMatrix;
  double radius;
};

float3 ToFloat3(const double3& v) { return {(float)v.x, (float)v.y, (float)v.z}; }
float4x4 ToFloat4x4(const double4x4& m)
{
  float4x4 out{};
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out.m[r][c] = (float)m.m[r][c];
  return out;
}
double3 Subtract(const double3& a, const double3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }

void UploadObject(void* mapped, const SceneObject& object, const double3& eye)
{
  ObjectConstants cb{};
  cb.World = ToFloat4x4(object.worldMatrix);
  cb.WorldPosition = ToFloat3(object.position);
  cb.Radius = (float)object.radius;
  // The split, done right for x and wrongly for y; z's halves stored the wrong way round.
  float xHi = (float)object.position.x;
  cb.PositionHigh.x = xHi;
  cb.PositionLow.x = (float)(object.position.x - xHi);
  float yHi = (float)object.position.y;
  cb.PositionHigh.y = yHi;
  cb.PositionLow.y = (float)object.position.y - yHi;
  float zHigh = (float)object.position.z;
  float zLow = (float)(object.position.z - zHigh);
  cb.PositionHigh.z = zLow;
  cb.PositionLow.z = zHigh;
  std::memcpy(mapped, &cb, sizeof cb);
}

// Right: relative to the eye, in double, before narrowing.
void UploadRelative(void* mapped, const SceneObject& object, const double3& eye)
{
  ObjectConstants cb{};
  cb.WorldPosition = ToFloat3(Subtract(object.position, eye));
  std::memcpy(mapped, &cb, sizeof cb);
}
