#include "cli/output_paths.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/error.h"
#include "mesh/mesh.h"

namespace prt::cli {

namespace {

namespace fs = std::filesystem;

constexpr std::size_t kMaxOutputNameLength = 224;

/// What a path names, to tell whether two paths are the same file: the device and inode where it
/// exists (hard links, symbolic links, any spelling), else the path with symbolic links, "." and ".."
/// resolved as far as it exists (lexically normalised and absolute where the system cannot resolve
/// it: a component too long, ...).
struct FileIdentity {
  fs::path resolved;
  bool exists = false;
  dev_t device = 0;
  ino_t inode = 0;
  bool operator==(const FileIdentity& o) const {
    return exists && o.exists ? device == o.device && inode == o.inode : resolved == o.resolved;
  }
};

FileIdentity identify(const std::string& path) {
  FileIdentity id;
  std::error_code ec;
  id.resolved = fs::weakly_canonical(fs::path(path), ec);
  if (ec) id.resolved = fs::absolute(fs::path(path), ec).lexically_normal();
  struct stat info;
  if (stat(path.c_str(), &info) == 0) {
    id.exists = true;
    id.device = info.st_dev;
    id.inode = info.st_ino;
  }
  return id;
}

void check_folder(const std::string& output) {
  std::error_code ec;
  fs::path folder = fs::path(output).parent_path();
  if (folder.empty()) folder = ".";
  check_output_target(output);  // a folder, device, FIFO or socket
  // The temporary sibling (AtomicFile) adds about 24 characters to the name; NAME_MAX is 255.
  const std::size_t name_length = fs::path(output).filename().string().size();
  if (name_length > kMaxOutputNameLength)
    fail_file(output, "file name is too long (" + std::to_string(name_length) + " characters; at most " +
                          std::to_string(kMaxOutputNameLength) + ")");
  if (!fs::is_directory(folder, ec)) fail_file(output, "output folder does not exist");
  // Create and remove a file there: permission bits alone say nothing for root, a read-only mount
  // or a pseudo file system such as /proc.
  const fs::path probe = folder / (".prt-write-check-" + std::to_string(getpid()));
  const int fd = open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0600);
  if (fd < 0) fail_file(output, std::string("output folder is not writable: ") + std::strerror(errno));
  close(fd);
  unlink(probe.c_str());
}

}  // namespace

void check_outputs(const std::vector<std::string>& outputs, const std::vector<std::string>& inputs) {
  std::vector<std::pair<FileIdentity, std::string>> seen;  // the inputs, then the outputs so far
  for (const std::string& input : inputs) {
    if (input.empty()) continue;
    seen.emplace_back(identify(input), input);
    for (const std::string& file : mesh::referenced_files(input))
      seen.emplace_back(identify(file), file + " (which " + input + " refers to)");
  }
  const std::size_t input_count = seen.size();
  for (const std::string& output : outputs) {
    if (output.empty()) continue;
    const FileIdentity id = identify(output);
    for (std::size_t k = 0; k < seen.size(); ++k) {
      if (!(seen[k].first == id)) continue;
      if (k < input_count)
        fail_file(output, "is also the input " + seen[k].second + "; prt does not overwrite its inputs");
      fail_file(output, "is given twice as an output (also as " + seen[k].second + ")");
    }
    check_folder(output);
    seen.emplace_back(id, output);
  }
}

}  // namespace prt::cli
