// libFuzzer target: .prtprobes files through parse_probe_file (preamble, JSON header, arrays, checks).
#include <string>

#include "fuzz_support.h"
#include "probes/probe_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  prt::fuzz::expect_result_or_error([&] { prt::probes::parse_probe_file(bytes, "input.prtprobes"); });
  return 0;
}
