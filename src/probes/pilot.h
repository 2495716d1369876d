#pragma once
// The pilot that decides, once per probe or surface point, whether its rays use the control-variate
// estimator or the plain one: kPilotRays occlusion rays of its own, from an independent direction set
// under a rotation hashed with kPilotSalt. The choice must not depend on the rays it applies to: a
// choice made per batch from that batch's own hit count correlates with the batch's quadrature error and
// biases the estimate (baker.h, ESTIMATOR).
#include <cstdint>

namespace prt::probes {

inline constexpr int kPilotRays = 16;
inline constexpr std::uint32_t kPilotSalt = 0x9170u;

}  // namespace prt::probes
