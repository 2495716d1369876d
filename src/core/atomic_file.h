#pragma once
// Output files that never exist half-written. A writer writes to a temporary sibling of the target,
// named ".<stem>.tmp-<pid>-<n><ext>" (same folder, so rename is atomic; same extension, so libraries
// that pick a format from the extension still do), and commit() renames it over the target. If the
// writer is destroyed without commit() (an error, an exception) the temporary is removed; on SIGINT or
// SIGTERM every live temporary is removed before the process exits with 128+signal.
// An existing target that is not a regular file (a device such as /dev/null, a FIFO, a socket, a
// folder) is refused, never renamed over (check_output_target).
#include <cstdint>
#include <fstream>
#include <functional>
#include <string>

namespace prt {

class AtomicFile {
 public:
  /// Prepares to write `path`. Nothing is created until stream() is called or a library writes to
  /// temp_path(). Throws Error if the target's folder does not exist or check_output_target refuses it.
  explicit AtomicFile(std::string path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  /// The final path.
  const std::string& path() const { return path_; }
  /// Where to write; for libraries that take a file name (OpenImageIO, tinygltf).
  const std::string& temp_path() const { return temp_; }
  /// A binary output stream on temp_path(), opened on first use. Throws Error if it cannot be opened.
  std::ofstream& stream();
  /// Flushes and closes the stream (if used), checks the target once more (check_output_target),
  /// then renames the temporary over path(). Throws Error naming path() if any of that failed.
  void commit();

 private:
  std::string path_;
  std::string temp_;
  std::ofstream out_;
  bool committed_ = false;
  int slot_ = -1;
};

/// Installs the SIGINT/SIGTERM handler that removes live temporaries and exits with 128+signal.
/// Called by the CLI at startup (and by every AtomicFile); idempotent.
void install_cleanup_signal_handlers();

/// Writes `bytes` to `path` through an AtomicFile.
void write_file_atomically(const std::string& path, const std::string& bytes);

/// The largest input file prt reads (4 GiB; docs/formats.md, "Limits").
inline constexpr unsigned long long kMaxInputBytes = 4ull << 30;

/// Throws Error("<path>: ...") unless `path` is a readable regular file of at most kMaxInputBytes:
/// folders, FIFOs (which would block) and devices such as /dev/zero (which never end) are refused.
void check_regular_input(const std::string& path);

/// The one way prt opens a file for reading: check_regular_input, then a binary stream positioned at
/// the start. Throws Error("<path>: cannot open: <reason>") if it cannot be opened.
std::ifstream open_input(const std::string& path);

/// The size in bytes of a stream from open_input (left at its start). Throws Error naming `path` if
/// it cannot be found.
std::uint64_t input_size(const std::string& path, std::ifstream& in);

/// Reads a whole file (through open_input). Throws Error("<path>: ...") if it cannot be read.
std::string read_file(const std::string& path);

/// Throws Error("<path>: ...") if `path` exists (symbolic links followed) and is not a regular file:
/// prt writes an output by renaming a new file into place, which would replace a device such as
/// /dev/null, a FIFO or a socket with a plain file; those and folders are refused instead
/// (docs/formats.md, "Limits"). A path that does not exist yet is fine.
void check_output_target(const std::string& path);

/// Writes one of several outputs into `file`'s temporary with `write` (a writer that takes a path),
/// so that every output can be committed together at the end and a failing second output leaves
/// no first one behind. An Error whose message names the temporary is rethrown naming file.path()
/// instead; any other exception passes unchanged.
void write_staged(AtomicFile& file, const std::function<void(const std::string&)>& write);

}  // namespace prt
