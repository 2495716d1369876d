#pragma once
// SH light probes in memory: where they are, what they store, which are valid. Every export
// (probes/<format>/README.md) and the .prtprobes file (probe_file.h) are written from a ProbeSet.
//
// CONVENTIONS
// - Positions: world frame of the scene (right-handed, +Y up, the scene file's units).
// - Coefficients: INCIDENT radiance at the probe over the whole sphere, projected onto prt's SH basis
//   (sh/basis.h: real orthonormal, WITH the Condon-Shortley phase, index l(l+1)+m, world directions),
//   in the environment image's linear units. A constant radiance L gives c_0 = 2 sqrt(pi) L. The
//   irradiance of a surface with normal n placed at the probe is sh::irradiance(probe, n).
// - Probe order: for a grid, index = x + NX (y + NY z) (x fastest); for a point list, file order.
// - GRID: `--grid NX,NY,NZ` divides the bounds box into NX x NY x NZ equal cells and puts one probe
//   at the centre of each cell: position = lo + (i + 1/2) (hi - lo) / N per axis. The probes never lie
//   on the box's faces (which are often walls or floors), and the box is exactly the volume an engine
//   that interpolates between cell centres (Bevy's irradiance volume) covers.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "sh/coefficients.h"

namespace prt::probes {

/// A regular grid of probes at cell centres (see GRID).
struct Grid {
  std::array<int, 3> counts{{0, 0, 0}};  ///< NX, NY, NZ >= 1
  glm::dvec3 lo{0.0}, hi{0.0};           ///< bounds box, lo <= hi per axis
};

/// Throws prt::Error with a one-line message unless every count is >= 1 (and NX NY NZ <= 2^26),
/// lo and hi are finite, and lo < hi on every axis (a box of zero or negative extent on any axis is
/// "empty": it holds no cells to put probes in).
void check_grid(const Grid& grid);

/// Probe positions of a grid, in probe order (x fastest). Precondition: check_grid passed.
std::vector<glm::dvec3> grid_positions(const Grid& grid);

/// Reads an explicit probe list. JSON: an array of [x, y, z] triples, or an object with "points"
/// holding such an array. CSV: one probe per line "x,y,z" (spaces allowed around values); empty lines
/// and lines starting with '#' are skipped; a first line that is not numeric is a header and skipped.
/// The format follows the extension (.json, .csv; any case). Throws prt::Error("<path>: <problem>") for
/// an unreadable file, another extension, malformed content (naming the line or entry), a non-finite
/// coordinate, or an empty list.
std::vector<glm::dvec3> read_points_file(const std::string& path);

/// Throws prt::Error("<name>: point <i> (x, y, z) is outside the scene bounds [lo] - [hi]") for the
/// first point outside the box [lo - margin, hi + margin], margin = 1e-4 of the box diagonal.
void check_points_inside(const std::vector<glm::dvec3>& points, const glm::dvec3& lo, const glm::dvec3& hi,
                         const std::string& name);

/// The probes, their coefficients and what the bake measured.
struct ProbeSet {
  enum class Layout { grid, points };
  Layout layout = Layout::points;
  Grid grid;                                ///< when layout == grid
  int bands = 3;                            ///< bands of every probe's coefficients (1..32)
  std::vector<glm::vec3> positions;         ///< one per probe
  /// Incident radiance coefficients, probe-major then coefficient (bands^2 RGB triples per probe).
  std::vector<glm::vec3> coefficients;
  /// 1 if the probe is usable; 0 if it lies inside geometry (backface_fraction above the threshold).
  std::vector<std::uint8_t> valid;
  /// Fraction of the probe's rays whose first hit was the back face of a triangle.
  std::vector<float> backface_fraction;
  /// The "sky probe": the environment plus the sun, unoccluded (what a probe in empty space would see).
  sh::RgbCoefficients sky;
  /// Optional relightable transfer (empty when transfer_bands == 0): per probe, for each of
  /// transfer_channels (1: grey, applies to r, g, b alike; 3: r, g, b) a bands^2 x transfer_bands^2
  /// row-major matrix M, so that the probe's coefficients are M L_env + bias, with L_env the
  /// environment's transfer_bands-band SH (prt basis, world frame). Probe-major, then channel, then row.
  int transfer_bands = 0;
  int transfer_channels = 0;
  std::vector<float> transfer;
  /// Per probe bands^2 RGB triples: the part that is not relit (sun and emission and their bounces).
  std::vector<glm::vec3> transfer_bias;
  /// The environment SH (transfer_bands bands) the transfer was baked with: M L_env + bias reproduces
  /// `coefficients` up to the band-limiting of the environment in the occluded directions.
  sh::RgbCoefficients transfer_environment;
  /// The sky probe's part that is not relit (the sun), `bands` bands: relighting sets
  /// sky = L_new (first min(bands, transfer_bands) bands) + sky_bias.
  sh::RgbCoefficients sky_bias;
  /// Bake parameters as a JSON object (text), stored in the file header for provenance.
  std::string parameters_json = "{}";

  std::size_t count() const { return positions.size(); }
  std::size_t coefficient_count() const { return static_cast<std::size_t>(bands) * bands; }
  std::size_t valid_count() const;
  /// Probe i's coefficients as an RgbCoefficients (double).
  sh::RgbCoefficients probe(std::size_t i) const;
  /// Values per probe of `transfer`: transfer_channels * bands^2 * transfer_bands^2.
  std::size_t transfer_values_per_probe() const;
};

/// Throws prt::Error("<name>: <problem>") if the arrays' sizes disagree with count(), bands or the
/// transfer dimensions, or a value is not finite. Every writer calls it first.
void check_probe_set(const ProbeSet& probes, const std::string& name);

/// Index of the probe nearest to `point` (ties: lowest index). Precondition: count() > 0.
std::size_t nearest_probe(const ProbeSet& probes, const glm::dvec3& point);

}  // namespace prt::probes
