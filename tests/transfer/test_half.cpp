#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <limits>

#include "transfer/half.h"

using prt::transfer::float_to_half;
using prt::transfer::half_to_float;

TEST_CASE("binary16 conversion of known values", "[transfer]") {
  CHECK(float_to_half(0.0f) == 0x0000);
  CHECK(float_to_half(-0.0f) == 0x8000);
  CHECK(float_to_half(1.0f) == 0x3c00);
  CHECK(float_to_half(-2.0f) == 0xc000);
  CHECK(float_to_half(65504.0f) == 0x7bff);
  CHECK(float_to_half(65520.0f) == 0x7c00);               // rounds to infinity
  CHECK(float_to_half(std::ldexp(1.0f, -24)) == 0x0001);  // smallest subnormal
  CHECK(float_to_half(std::ldexp(1.0f, -25)) == 0x0000);  // tie rounds to even (0)
  CHECK(float_to_half(std::ldexp(3.0f, -25)) == 0x0002);  // 1.5 ulp rounds to 2
  CHECK(float_to_half(std::numeric_limits<float>::infinity()) == 0x7c00);
  CHECK((float_to_half(std::numeric_limits<float>::quiet_NaN()) & 0x7c00) == 0x7c00);
  CHECK(float_to_half(1.0f + std::ldexp(1.0f, -11)) == 0x3c00);       // tie to even, down
  CHECK(float_to_half(1.0f + 3 * std::ldexp(1.0f, -11)) == 0x3c02);   // tie to even, up
}

TEST_CASE("every binary16 value round-trips through float exactly", "[transfer]") {
  for (std::uint32_t h = 0; h < 0x10000; ++h) {
    float f = half_to_float(static_cast<std::uint16_t>(h));
    if (std::isnan(f)) continue;
    REQUIRE(float_to_half(f) == h);
  }
}

TEST_CASE("float to half rounds to the nearest representable value", "[transfer]") {
  // For floats in the normal half range the result is within half an ulp (2^-11 relative).
  for (float x = 6.2e-5f; x < 60000.0f; x *= 1.0137f) {
    float back = half_to_float(float_to_half(x));
    REQUIRE(std::abs(back - x) <= x * std::ldexp(1.0f, -11) * 1.0001f);
  }
}
