#pragma once
// What the distributed commands (bake, probes, reference) share: the job's ranks, and the
// fingerprints of their inputs that every rank compares before the work starts (docs/distributed.md).
// Run without mpirun the job is this process alone and every call here costs nothing.
#include <string>
#include <vector>

#include "dist/context.h"
#include "dist/inputs.h"
#include "light/environment.h"
#include "mesh/mesh.h"

namespace prt::cli {

/// The job this command runs in (dist::Context::world()).
dist::Context& job();

/// Fingerprint of everything the work reads from a loaded mesh: positions, normals, albedo, emission
/// and indices; named by `path`.
dist::Fingerprint mesh_input(const std::string& path, const mesh::Mesh& mesh);

/// Fingerprint of an environment's layout, sizes and pixels; named by `spec`.
dist::Fingerprint environment_input(const std::string& spec, const light::Environment& environment);

/// Fingerprint of a command's canonical option string (every option that changes the output, parsed:
/// a BRDF file enters as its parsed spec, so its content is checked too); named "the options".
dist::Fingerprint options_input(const std::string& canonical);

/// On more than one rank: compares `inputs` across ranks (dist::check_same_inputs: a CollectiveError
/// on every rank if any differs). A no-op on one rank.
void check_job_inputs(const std::vector<dist::Fingerprint>& inputs);

/// For a command's summary line: "" on one rank, else ", N ranks (rank 0: X MB exchanged in E s after
/// waiting W s for the others)".
std::string job_summary();

/// The exact text of a float (hexadecimal), for canonical option strings.
std::string exact(double value);

}  // namespace prt::cli
