// A few declarations with the names of Apple's <simd/simd.h>, written for lwcport's corpus: vectors of
// the compiler's own (ext_vector_type) and the conversions between float and double ones.
#pragma once
typedef float simd_float2 __attribute__((ext_vector_type(2)));
typedef float simd_float3 __attribute__((ext_vector_type(3)));
typedef float simd_float4 __attribute__((ext_vector_type(4)));
typedef double simd_double2 __attribute__((ext_vector_type(2)));
typedef double simd_double3 __attribute__((ext_vector_type(3)));
typedef double simd_double4 __attribute__((ext_vector_type(4)));
typedef struct { simd_float4 columns[4]; } simd_float4x4;
inline simd_float2 simd_float(simd_double2 v) { return __builtin_convertvector(v, simd_float2); }
inline simd_float3 simd_float(simd_double3 v) { return __builtin_convertvector(v, simd_float3); }
inline simd_double3 simd_double(simd_float3 v) { return __builtin_convertvector(v, simd_double3); }
