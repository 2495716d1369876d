#include "core/atomic_file.h"

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <sstream>

#include <sys/stat.h>
#include <unistd.h>

#include "core/error.h"

namespace prt {

namespace {

// Live temporaries, kept in fixed storage so the signal handler can unlink them without allocating.
constexpr int kMaxLive = 64;
constexpr int kMaxPath = 4096;
char g_live_paths[kMaxLive][kMaxPath];
std::atomic<bool> g_live_used[kMaxLive];
std::mutex g_register_mutex;
std::atomic<int> g_counter{0};

extern "C" void remove_temporaries_and_exit(int sig) {
  for (int i = 0; i < kMaxLive; ++i)
    if (g_live_used[i].load()) unlink(g_live_paths[i]);
  _exit(128 + sig);
}

}  // namespace

void install_cleanup_signal_handlers() {
  static bool installed = [] {
    struct sigaction sa;
    std::memset(&sa, 0, sizeof sa);
    sa.sa_handler = remove_temporaries_and_exit;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);
    return true;
  }();
  (void)installed;
}

namespace {

int register_temporary(const std::string& temp) {
  std::lock_guard<std::mutex> lock(g_register_mutex);
  if (temp.size() >= kMaxPath) return -1;
  for (int i = 0; i < kMaxLive; ++i) {
    if (!g_live_used[i].load()) {
      std::memcpy(g_live_paths[i], temp.c_str(), temp.size() + 1);
      g_live_used[i].store(true);
      return i;
    }
  }
  return -1;
}

void unregister_temporary(int slot) {
  if (slot < 0) return;
  std::lock_guard<std::mutex> lock(g_register_mutex);
  g_live_used[slot].store(false);
}

}  // namespace

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
  namespace fs = std::filesystem;
  fs::path target(path_);
  fs::path dir = target.parent_path();
  if (!dir.empty() && !fs::is_directory(dir)) fail_file(path_, "output folder does not exist");
  check_output_target(path_);
  std::ostringstream name;
  name << "." << target.stem().string() << ".tmp-" << getpid() << "-" << g_counter.fetch_add(1)
       << target.extension().string();
  temp_ = (dir / name.str()).string();
  install_cleanup_signal_handlers();
  slot_ = register_temporary(temp_);
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    if (out_.is_open()) out_.close();
    std::remove(temp_.c_str());
  }
  unregister_temporary(slot_);
}

std::ofstream& AtomicFile::stream() {
  if (!out_.is_open()) {
    out_.open(temp_, std::ios::binary | std::ios::trunc);
    if (!out_) fail_file(path_, "cannot open for writing");
  }
  return out_;
}

void AtomicFile::commit() {
  if (out_.is_open()) {
    out_.flush();
    bool ok = static_cast<bool>(out_);
    out_.close();
    if (!ok) fail_file(path_, "write failed (disk full?)");
  }
  check_output_target(path_);  // it may have appeared since the constructor
  if (std::rename(temp_.c_str(), path_.c_str()) != 0)
    fail_file(path_, std::string("cannot rename temporary into place: ") + std::strerror(errno));
  committed_ = true;
}

void check_regular_input(const std::string& path) {
  struct stat info;
  if (stat(path.c_str(), &info) != 0) fail_file(path, std::string("cannot open: ") + std::strerror(errno));
  if (S_ISDIR(info.st_mode)) fail_file(path, "is a folder, not a file");
  // A FIFO blocks and a device such as /dev/zero never ends: only regular files are inputs.
  if (!S_ISREG(info.st_mode)) fail_file(path, "is not a regular file (a pipe, socket or device)");
  if (static_cast<unsigned long long>(info.st_size) > kMaxInputBytes)
    fail_file(path, "is larger than " + std::to_string(kMaxInputBytes >> 30) + " GiB, the most prt reads");
}

void check_output_target(const std::string& path) {
  struct stat info;
  if (stat(path.c_str(), &info) != 0) return;  // not there yet (or unreachable: the write will say)
  if (S_ISDIR(info.st_mode)) fail_file(path, "is a folder; an output must be a file path");
  if (!S_ISREG(info.st_mode))
    fail_file(path, "is not a regular file (a pipe, socket or device); prt replaces an output by renaming a new "
                    "file over it and refuses to do that to one of these: write to a file instead");
}

std::ifstream open_input(const std::string& path) {
  check_regular_input(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) fail_file(path, std::string("cannot open: ") + std::strerror(errno));
  return in;
}

std::uint64_t input_size(const std::string& path, std::ifstream& in) {
  in.seekg(0, std::ios::end);
  const auto end = in.tellg();
  in.seekg(0, std::ios::beg);
  if (end < 0) fail_file(path, "cannot determine file size");
  return static_cast<std::uint64_t>(end);
}

void write_file_atomically(const std::string& path, const std::string& bytes) {
  AtomicFile file(path);
  file.stream().write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  file.commit();
}

std::string read_file(const std::string& path) {
  std::ifstream in = open_input(path);
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) fail_file(path, "read failed");
  return ss.str();
}

void write_staged(AtomicFile& file, const std::function<void(const std::string&)>& write) {
  try {
    write(file.temp_path());
  } catch (const Error& e) {
    std::string message = e.what();
    if (message.find(file.temp_path()) == std::string::npos) throw;
    for (std::size_t at = message.find(file.temp_path()); at != std::string::npos;
         at = message.find(file.temp_path(), at + file.path().size()))
      message.replace(at, file.temp_path().size(), file.path());
    throw Error(message);
  }
}

}  // namespace prt
