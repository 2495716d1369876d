#pragma once
// Relighting with baked transfer on the CPU: the reference for what shaders compute.
#include <vector>

#include <glm/vec3.hpp>

#include "sh/coefficients.h"
#include "transfer/transfer_file.h"

namespace prt::shade {

/// Per-vertex outgoing radiance (linear RGB, the lighting's units) of a diffuse transfer under distant
/// lighting given by world-frame radiance coefficients: out[v].c = sum_i T[v][c'][i] L[i].c with
/// c' = c for 3-channel transfer and 0 for 1-channel transfer, over the transfer's bands^2 coefficients.
/// Lighting with more bands is truncated; with fewer bands the missing coefficients count as zero.
/// Precondition: a diffuse kind (unshadowed, shadowed, interreflected). Accumulates in double.
std::vector<glm::vec3> shade_diffuse(const transfer::TransferData& transfer, const sh::RgbCoefficients& lighting);

/// The run-time band choice (`--bands N` of shade, render and view; docs/conventions.md, "Run-time
/// band truncation"): the number of lighting bands a transfer of header.bands bands is shaded with.
/// `requested` 0 means all of the transfer's bands; 1..header.bands truncates the lighting to that many
/// whole bands (every coefficient of band l >= N is dropped, the transfer's own values are kept; glossy:
/// the input side only, the output bands stay). Throws prt::OptionError (field "bands") otherwise.
int shading_bands(const transfer::Header& header, int requested);

}  // namespace prt::shade
