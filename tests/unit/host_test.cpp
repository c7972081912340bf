// The host half: splitting doubles into High/Low and tile/offset.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "shaderlib/lwc_host.h"

namespace lwc::host {
namespace {

TEST(HostSplit, HighIsTheNearestFloatAndLowIsCanonical) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> exponent(0, 43), sign(-1, 1);
  for (int i = 0; i < 100000; ++i) {
    double v = std::copysign(std::exp2(exponent(rng)), sign(rng));
    HighLow s = split(v);
    EXPECT_EQ(s.high, static_cast<float>(v));
    // |Low| <= ulp(High) / 2, and High + Low in float is High.
    EXPECT_LE(std::fabs(s.low), std::fabs(std::nextafter(s.high, INFINITY) - s.high) / 2 * 1.0000001);
    EXPECT_EQ(s.high + s.low, s.high);
    // The pair keeps 48 bits: the error is at most half a float ulp of Low.
    EXPECT_LE(std::fabs(join(s) - v), std::ldexp(std::fabs(v), -48)) << v;
  }
}

TEST(HostSplit, ObjectCloseToAFarCameraKeepsItsOffset) {
  // An object 12.34 cm from a camera 2^42 cm from the origin (LWC-BRIEF §6).
  double camera = std::ldexp(1.0, 42), object = camera + 12.34;
  HighLow c = split(camera), o = split(object);
  float offset = (o.high - c.high) + (o.low - c.low);
  EXPECT_NEAR(offset, 12.34, 1e-3);
  EXPECT_NE(static_cast<float>(object) - static_cast<float>(camera), 12.34f);  // float32 alone cannot
}

TEST(HostTileOffset, RoundTripsAndKeepsOffsetWithinHalfATile) {
  for (double tile_size : {tile_size_ue54, tile_size_docs}) {
    for (double v : {0.0, 1e5, 0.5 * tile_size, 2.5 * tile_size, -2.5 * tile_size, 3 * tile_size - 0.5, std::ldexp(1.0, 42)}) {
      TileOffset t = to_tile_offset(v, tile_size);
      EXPECT_LE(std::fabs(t.offset), tile_size / 2) << v;
      EXPECT_NEAR(from_tile_offset(t, tile_size), v, std::ldexp(tile_size, -24)) << v;
    }
  }
  // The half-tile tie rounds up on the host (floor(x + 0.5)); a GPU's round-to-even differs there.
  EXPECT_EQ(to_tile_offset(2.5 * tile_size_ue54).tile, 3.0f);
}

}  // namespace
}  // namespace lwc::host
