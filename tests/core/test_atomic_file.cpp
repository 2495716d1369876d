#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "core/atomic_file.h"
#include "core/error.h"

namespace fs = std::filesystem;

namespace {
fs::path fresh_dir(const char* name) {
  fs::path dir = fs::temp_directory_path() / "prt_test_core" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}
std::size_t file_count(const fs::path& dir) {
  std::size_t n = 0;
  for (auto& entry : fs::directory_iterator(dir)) { (void)entry; ++n; }
  return n;
}
}  // namespace

TEST_CASE("AtomicFile commits by renaming the temporary over the target", "[core]") {
  fs::path dir = fresh_dir("commit");
  fs::path target = dir / "out.bin";
  {
    prt::AtomicFile file(target.string());
    file.stream() << "hello";
    CHECK(fs::exists(file.temp_path()));
    CHECK_FALSE(fs::exists(target));
    CHECK(fs::path(file.temp_path()).extension() == ".bin");
    file.commit();
  }
  CHECK(prt::read_file(target.string()) == "hello");
  CHECK(file_count(dir) == 1);
}

TEST_CASE("AtomicFile leaves nothing behind when not committed", "[core]") {
  fs::path dir = fresh_dir("abort");
  fs::path target = dir / "out.bin";
  try {
    prt::AtomicFile file(target.string());
    file.stream() << "partial";
    throw std::runtime_error("simulated failure");
  } catch (const std::runtime_error&) {
  }
  CHECK(file_count(dir) == 0);
}

TEST_CASE("AtomicFile rejects a missing output folder with the path in the message", "[core]") {
  fs::path target = fs::temp_directory_path() / "prt_no_such_dir_xyz" / "out.bin";
  try {
    prt::AtomicFile file(target.string());
    FAIL("expected an error");
  } catch (const prt::Error& e) {
    CHECK(std::string(e.what()).find("out.bin: output folder does not exist") != std::string::npos);
  }
}

TEST_CASE("read_file names the file it cannot open", "[core]") {
  try {
    prt::read_file("/nonexistent/file.txt");
    FAIL("expected an error");
  } catch (const prt::Error& e) {
    CHECK(std::string(e.what()).rfind("/nonexistent/file.txt: cannot open", 0) == 0);
  }
}
