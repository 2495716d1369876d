// libFuzzer target: compressed transfer files (.cprt, versions 1 and 2) through read_transfer_or_cprt,
// which reads the header, checksums and payload and then decompresses the model, so cluster ids,
// weights and the texel mask that pass the reader are also used.
#include "compress/cprt_file.h"
#include "compress/open_transfer.h"
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = prt::fuzz::write_input(data, size, "input.cprt");
  prt::fuzz::expect_result_or_error([&] { prt::compress::expand(prt::compress::open_transfer(path)); });
  return 0;
}
