#pragma once
// Dominant lights out of an environment map: finds the compact, very bright sources of an HDR map (a
// sun, a few lamps), fits each as a Disc (light/disc.h) that conserves its energy, and removes it from
// the map by filling its texels from the surrounding sky, so that the residual projects to SH without
// the spike. The rule, its thresholds and its limits: docs/conventions.md, "Sun and sky".
//
// RULE (equirect maps; cube maps are first resampled to an equirect map of 4N x 2N):
//  1. Luminance Y = 0.2126 R + 0.7152 G + 0.0722 B per texel; the SKY LEVEL S is the solid-angle-weighted
//     median of Y.
//  2. Seeds: texels with Y > max(kSeedContrast S, kSeedPeakFraction Y_max). Seeds are grouped into
//     8-connected regions (wrapping in phi).
//  3. A region is a disc candidate if its peak is > kPeakContrast S and it is compact: its core (the
//     seeds) subtends at most kMaxCoreRadiusDegrees.
//  4. Its MASK is every texel within (core radius + kMaskMarginTexels texel widths) of the core's
//     luminance-weighted centroid; mask texels are refilled by inverse-distance-squared interpolation of
//     the ring of texels just outside the mask (the surrounding sky).
//  5. The disc: direction d = the normalised sum of (L - fill) luminance x solid angle x direction over
//     the mask; E = sum over the mask of (L - fill) Omega (d . w) per channel (irradiance at normal
//     incidence, so the disc and the removed texels deliver the same energy to a surface facing d);
//     radius from the second moment of the excess about d: a uniform cap of radius a has mean squared
//     angle a^2 / 2, so a = sqrt(2 <theta^2>), at least half a texel.
//  6. A disc is kept if it carries at least kMinPowerFraction of the map's total power (sum Y Omega);
//     at most kMaxDiscs discs, brightest E first.
// A sky with no such source (overcast, broad soft light) yields no disc and an unchanged map. Studio soft
// boxes of a few degrees are compact sources: they become discs (round, uniform, with the boxes' energy),
// which shades them far closer to the truth than low-order SH can (docs/conventions.md).
#include <vector>

#include "light/disc.h"
#include "light/environment.h"

namespace prt::light {

inline constexpr double kSeedContrast = 200.0;        ///< seeds: Y > this x the sky level ...
inline constexpr double kSeedPeakFraction = 0.05;     ///< ... and > this x the region's peak luminance
inline constexpr double kPeakContrast = 1000.0;       ///< a disc's peak: > this x the sky level
inline constexpr double kMaxCoreRadiusDegrees = 10.0; ///< compactness of the seeds (or 1.5 texel widths, if larger)
inline constexpr double kMaskMarginTexels = 2.0;      ///< mask = core + this many texel widths
inline constexpr double kMinPowerFraction = 0.02;     ///< a disc carries >= 2% of the map's power
inline constexpr int kMaxDiscs = 4;

/// What extraction found and did.
struct ExtractionResult {
  std::vector<Disc> discs;   ///< brightest first; empty when the map has no dominant light
  Environment residual;      ///< with discs: the map with their texels refilled (equirect); without: empty
                             ///< (the input stands unchanged: no copy is made)
  double sky_level = 0.0;    ///< S, the solid-angle-weighted median luminance
  std::vector<int> masked_texels;  ///< per disc: texels refilled
};

/// Finds and removes the dominant lights of `environment` (see RULE), at most `max_discs` (1..kMaxDiscs)
/// of them. Deterministic; `threads` <= 0 uses all cores. The residual of a cube map is an equirect map
/// (see RULE).
ExtractionResult extract_discs(const Environment& environment, int threads = 0, int max_discs = kMaxDiscs);

}  // namespace prt::light
