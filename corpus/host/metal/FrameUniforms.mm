// An Objective-C++ Metal renderer's frame uniforms, filled from double positions kept in Apple's
// simd vectors.
#include "simd_mini.h"

struct FrameUniforms {
  simd_float2 cursor;
  simd_float4x4 viewProjection;
  simd_float3 sunPosition;
  simd_float3 eyeFromSun;
};

struct Body {
  simd_double3 position;
};

void FillFrame(FrameUniforms& frame, const Body& eye, const Body& sun, simd_double2 pos)
{
  frame.sunPosition = simd_float(sun.position);
  // Right: the eye relative to the sun, a difference of two positions in double.
  frame.eyeFromSun = __builtin_convertvector(eye.position - sun.position, simd_float3);
  // Right: two numbers named as a position are the pointer's place on the screen.
  frame.cursor = simd_float(pos);
}

void FillEye(FrameUniforms& frame, const Body& eye, simd_double3 anchor)
{
  // Right: relative to a point the tables do not know, in double.
  frame.eyeFromSun = __builtin_convertvector(eye.position - anchor, simd_float3);
  // A world position a constant away is a world position still.
  frame.eyeFromSun = __builtin_convertvector(eye.position - simd_double3{0.0, 0.0, 1.5}, simd_float3);
}
