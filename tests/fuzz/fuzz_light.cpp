// libFuzzer target: SH lighting JSON files through read_light_file.
#include "fuzz_support.h"
#include "light/light_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = prt::fuzz::write_input(data, size, "input.json");
  prt::fuzz::expect_result_or_error([&] { prt::light::read_light_file(path); });
  return 0;
}
