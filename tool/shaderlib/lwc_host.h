#pragma once
// The host half of the DoubleFloat library: how a C++ engine fills the uniforms that the shader
// side (lwc_doublefloat.hlsl / .glsl) reads. Header-only and dependency-free so that an engine can
// take it as is. Keep positions and world matrices in double on the host; split them only when
// uploading.
#include <cmath>

namespace lwc::host {

// A double as High + Low floats: High is the nearest float, Low the nearest float to the rest.
// High + Low carries about 48 significant bits, enough for any position below UE's 2^43 cm
// limit to 2^-5 cm. Never let the compiler contract or reassociate these two lines (no -ffast-math).
struct HighLow {
  float high = 0;
  float low = 0;
};

inline HighLow split(double value) {
  HighLow r;
  r.high = static_cast<float>(value);
  r.low = static_cast<float>(value - static_cast<double>(r.high));
  return r;
}

inline double join(HighLow v) { return static_cast<double>(v.high) + static_cast<double>(v.low); }

// UE 5.0-5.3 tile/offset form: value = tile * tile_size + offset, the tile rounded to nearest so
// that |offset| <= tile_size / 2. Precision then depends on where the value sits within its tile.
struct TileOffset {
  float tile = 0;
  float offset = 0;
};

inline constexpr double tile_size_ue54 = 2097152.0;  // 2^21, UE 5.4-era engine headers
inline constexpr double tile_size_docs = 262144.0;   // 2^18, the "256k" of the LWC docs

inline TileOffset to_tile_offset(double value, double tile_size = tile_size_ue54) {
  TileOffset r;
  double tile = std::floor(value / tile_size + 0.5);
  r.tile = static_cast<float>(tile);
  r.offset = static_cast<float>(value - tile * tile_size);
  return r;
}

inline double from_tile_offset(TileOffset v, double tile_size = tile_size_ue54) {
  return static_cast<double>(v.tile) * tile_size + static_cast<double>(v.offset);
}

}  // namespace lwc::host
