#pragma once
// IEEE 754 binary16 conversion (round to nearest even, with subnormals, infinities and NaN).
#include <cstdint>

namespace prt::transfer {

std::uint16_t float_to_half(float value);
float half_to_float(std::uint16_t half);

}  // namespace prt::transfer
