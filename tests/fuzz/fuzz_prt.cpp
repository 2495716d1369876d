// libFuzzer target: .prt transfer files through read_transfer (header, checksums, payload range).
#include "fuzz_support.h"
#include "transfer/transfer_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = prt::fuzz::write_input(data, size, "input.prt");
  prt::fuzz::expect_result_or_error([&] { prt::transfer::read_transfer(path); });
  return 0;
}
