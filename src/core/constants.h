#pragma once
// Mathematical constants, in double precision (cast where float is wanted).

namespace prt {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kInvPi = 0.31830988618379067154;

}  // namespace prt
