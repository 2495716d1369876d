// libFuzzer target: BRDF files. An input starting with "PRTBRDF1" is a binary BRDF matrix (.bin);
// anything else is JSON, read both as a BRDF matrix (.json) and as a material file (parse_brdf).
#include <cstring>

#include "brdf/brdf.h"
#include "brdf/brdf_file.h"
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size >= 8 && std::memcmp(data, "PRTBRDF1", 8) == 0) {
    const std::string path = prt::fuzz::write_input(data, size, "input.bin");
    prt::fuzz::expect_result_or_error([&] { prt::brdf::read_brdf_matrix(path); });
    return 0;
  }
  const std::string path = prt::fuzz::write_input(data, size, "input.json");
  prt::fuzz::expect_result_or_error([&] { prt::brdf::read_brdf_matrix(path); });
  prt::fuzz::expect_result_or_error([&] { prt::brdf::parse_brdf(path); });
  return 0;
}
