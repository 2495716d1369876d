#pragma once
// Checks a subcommand runs on its output paths before any slow work.
#include <string>
#include <vector>

#include "core/atomic_file.h"

namespace prt::cli {

/// Throws prt::Error, before anything is computed or written, if an output (empty strings are
/// skipped):
/// - is the same file as an input or as another output: by device and inode where both exist (hard
///   links), else after canonicalising both ("dir/./x", "a/../x", symbolic links):
///   "<output>: is also the input <input>; ...". A mesh input's referenced files (its MTL files,
///   glTF buffers and images: mesh::referenced_files) are inputs too;
/// - lies in a folder that does not exist or that this process cannot write to;
/// - exists and is not a regular file (check_output_target: a folder, device, FIFO or socket), or
///   has a file name longer than 224 characters (room for the temporary's).
void check_outputs(const std::vector<std::string>& outputs, const std::vector<std::string>& inputs);

}  // namespace prt::cli
