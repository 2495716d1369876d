// libFuzzer target: probe position lists through read_points_file; an input whose first non-blank
// byte is '[' or '{' is read as .json, anything else as .csv.
#include <string>

#include "fuzz_support.h"
#include "probes/probe_set.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::size_t first = text.find_first_not_of(" \t\r\n");
  const bool json = first != std::string::npos && (text[first] == '[' || text[first] == '{');
  const std::string path = prt::fuzz::write_input(data, size, json ? "input.json" : "input.csv");
  prt::fuzz::expect_result_or_error([&] { prt::probes::read_points_file(path); });
  return 0;
}
