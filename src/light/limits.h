#pragma once
// The largest lighting value prt accepts, in any unit the user's files carry (radiance in an
// environment map, an SH lighting coefficient, a disc's irradiance or angle as given on --sun):
// 1e18 in magnitude. With transfer values <= 1e15 and at most 3 x 1024 coefficients, relit values
// stay far below FLT_MAX (docs/formats.md, "Limits"). A file over it is refused with one line.
namespace prt::light {

inline constexpr double kMaxLightValue = 1e18;

}  // namespace prt::light
