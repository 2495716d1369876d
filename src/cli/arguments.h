#pragma once
// Parsing of the comma-separated option values shared by several subcommands.
#include <string>

#include <glm/vec3.hpp>

#include "image/image.h"
#include "mesh/mesh.h"

namespace CLI {
class App;
}

namespace prt::cli {

/// Adds `--footprint area|vertex` to `cmd`, its default the value `value` holds: where the
/// per-vertex estimates start (mesh/vertex_footprint.h); `what` says what the vertex's value then is.
/// Parse the value with mesh::parse_footprint.
void add_footprint_option(CLI::App* cmd, std::string& value, const std::string& what);

/// Parses "A,B,C" into three doubles of magnitude at most mesh::kMaxCoordinate (1e12: positions,
/// colours and angles beyond it overflow float maths downstream). Throws prt::Error("<option>: expected <what>, got '<text>'").
glm::dvec3 parse_triple(const std::string& text, const std::string& option, const std::string& what);

/// Parses "YAW,PITCH,ROLL" (degrees) into the active rotation Ry(yaw) Rx(pitch) Rz(roll) angles.
glm::dvec3 parse_angles(const std::string& text, const std::string& option);

/// Parses --tone-map: "aces" or "clamp" (image::to_display's operators). Throws
/// prt::Error("--tone-map: expected aces or clamp, got '<name>'").
image::ToneMap parse_tone_map(const std::string& name);

/// True if stderr is a terminal and `quiet` is not set: whether to draw progress bars.
bool want_progress(bool quiet);

/// load_mesh for a command with --albedo: where `albedo` (the flag's text) is given and the file has an
/// albedo of its own, prints "<path>: --albedo R,G,B overrides the file's <source> albedo" (unless
/// `quiet`) and drops the file's (mesh::drop_albedo), so that the option's albedo applies everywhere.
mesh::Mesh load_mesh_for_albedo(const std::string& path, const std::string& albedo, const mesh::LoadOptions& options,
                                 mesh::LoadReport* report = nullptr);

/// Parses "K,N" (two integers: clusters, PCA vectors); false if the text is not of that form.
bool parse_compress_setting(const std::string& text, int& clusters, int& pca);

/// The command-line flag of an options field named in a library's OptionError: "--" and the field with
/// '_' as '-' ("sun_samples" -> "--sun-samples"), except the fields whose flag is spelled otherwise.
std::string flag_of_field(const std::string& field);

/// Parses --scene: "all" (mesh::kAllScenes) or a scene index 0..2^31-1. Throws
/// prt::Error("--scene: expected a scene index (0, 1, ...) or all, got '<text>'").
int parse_scene(const std::string& text);

/// Adds `--scene N|all` to `cmd`, a command that loads a mesh: which glTF scene it reads, parsed into
/// `scene` (mesh::LoadOptions::scene; left as it is, mesh::kDefaultScene, when the flag is absent).
void add_scene_option(CLI::App* cmd, int& scene);

}  // namespace prt::cli
