#pragma once
// Probe exports for engines. Each format's exact layout, units, frame and scaling is specified in
// probes/<format>/README.md; the per-coefficient maths is in engine_sh.h. All files are written
// atomically. Invalid probes (inside geometry) are marked invalid where the format can say so and
// left out where it cannot (see each function).
#include <cstddef>
#include <string>
#include <vector>

#include "probes/probe_set.h"
#include "transfer/ktx2.h"

namespace prt::light {
struct Environment;
}

namespace prt::probes {

enum class Format { prt, threejs, unity, godot, filament, gltf, bevy };

/// Parses "prt", "threejs", "unity", "godot", "filament", "gltf", "bevy"; throws
/// prt::Error("--format: unknown format '<name>' (expected prt, threejs, unity, godot, filament, gltf or bevy)").
Format parse_format(const std::string& name);
const char* format_name(Format format);

/// What some exporters need beyond the probes.
struct ExportOptions {
  /// filament: "sky" (the sky probe) or a probe index. gltf always exports the sky probe.
  std::string probe = "sky";
  /// gltf: the scene file to re-write (.gltf, .glb; any other mesh format is written as one mesh).
  std::string scene_path;
  /// gltf: the environment, for the specular cube map images Babylon.js requires (nullptr: the sky
  /// probe's SH reconstruction is used instead).
  const light::Environment* environment = nullptr;
  /// gltf: edge of the largest specular cube face, a power of two in 1..1024.
  int specular_size = 64;
};

/// Writes `probes` as `format` to `path`. Throws prt::Error naming the file or option on failure
/// (e.g. a Filament probe index out of range or invalid; a Bevy export of a point list).
void export_probes(const ProbeSet& probes, Format format, const std::string& path, const ExportOptions& options);

/// three.js probe volume (probes/threejs/README.md), read by probes/threejs/prt_probe_volume.js:
/// JSON {"format": "prt-probe-volume-threejs", "version": 2, "frame", "sh_layout", "count", "layout"
/// (grid counts, bounds, order, cell centres; or points), "positions" (3 floats per probe), "valid"
/// (1/0 per probe), "sh" (27 floats per probe: threejs_coefficients, SphericalHarmonics3 order),
/// "sky" (27 floats)}. Every probe is listed; invalid ones (inside geometry) have valid 0.
std::string format_threejs(const ProbeSet& probes);

/// Unity: JSON for probes/unity/PrtProbeImporter.cs: per probe "index", "position" (Unity frame),
/// "valid", "sh" (27 floats, SphericalHarmonicsL2 order sh[channel * 9 + i], unity_coefficients).
std::string format_unity(const ProbeSet& probes);

/// Godot: JSON for probes/godot/prt_probe_import.gd: per probe "index", "position", "valid",
/// "sh" (27 floats, 9 colours r,g,b: godot_coefficients).
std::string format_godot(const ProbeSet& probes);

/// Filament: cmgen's sh.txt format: 9 lines "(r, g, b); // L<l><m>, irradiance, pre-scaled base"
/// (std::fixed, 15 decimals, width 18, as cmgen's outputSh), filament_coefficients of the chosen probe.
std::string format_filament(const ProbeSet& probes, const std::string& probe);

/// Bevy: a KTX2 file (VK_FORMAT_R16G16B16A16_SFLOAT, 3D, one level) of size (NX, 2 NY, 3 NZ) holding the
/// ambient cube of every grid probe: texel (x, y + NY s, z + NZ a) = C(axis a, sign s) of probe
/// (x, y, z), a = 0 X, 1 Y, 2 Z; s = 0 positive, 1 negative (the order Bevy's shader reads). Invalid
/// probes cannot be left out of a texture: their cells are filled from their valid neighbours
/// (repeated 6-neighbour averaging, "dilation"); with no valid probe at all the export fails.
/// Precondition (else prt::Error): layout == grid.
std::string format_bevy_ktx2(const ProbeSet& probes);

/// The probe coefficients Bevy's texture is made from after dilation of invalid probes (exposed for tests).
std::vector<glm::vec3> dilate_invalid(const ProbeSet& probes);

/// Parses a KTX2 file written by format_bevy_ktx2 back into its float texels (RGBA, x fastest) and
/// size, checking the identifier, format, DFD and level index. For tests and `prt info`-like tools.
using Ktx2Texture = transfer::Ktx2Image;
Ktx2Texture read_bevy_ktx2(const std::string& bytes, const std::string& name);

/// glTF: writes a .glb (path must end in .glb) of the scene with EXT_lights_image_based (one light,
/// "irradianceCoefficients" = gltf_irradiance_coefficients of the sky probe, intensity 1, rotation
/// identity, specular cube images RGBD-encoded PNGs with straight alpha, each face mirrored in x into
/// Babylon.js's frame and stored bottom row first; see probes/gltf/README.md) referenced by every scene.
void write_gltf(const ProbeSet& probes, const std::string& path, const ExportOptions& options);

}  // namespace prt::probes
