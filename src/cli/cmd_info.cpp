// prt info: prints the header of a prt file (transfer .prt files; SH lighting .json files).
#include <cstdio>
#include <fstream>

#include "cli/commands.h"
#include "compress/cprt_file.h"
#include "core/error.h"
#include "light/light_file.h"
#include "transfer/transfer_file.h"

namespace prt::cli {

namespace {

void run_info(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail_file(path, "cannot open");
  char magic[8] = {};
  in.read(magic, 8);
  const std::string head(magic, static_cast<std::size_t>(in.gcount()));
  if (head == std::string("PRTXFER\0", 8)) {
    std::printf("%s: prt transfer file\n%s", path.c_str(), transfer::describe(transfer::read_transfer_header(path)).c_str());
    return;
  }
  if (head == std::string(compress::kCprtMagic, 8)) {
    std::printf("%s: prt compressed transfer file\n%s", path.c_str(), compress::describe(compress::read_cprt_header(path)).c_str());
    return;
  }
  if (!head.empty() && head[0] == '{') {
    const sh::RgbCoefficients c = light::read_light_file(path);
    std::printf("%s: SH lighting (radiance)\nbands: %d (%d coefficients)\nL00 (r,g,b): %.6g %.6g %.6g\n", path.c_str(), c.bands,
                c.bands * c.bands, c.values[0].r, c.values[0].g, c.values[0].b);
    return;
  }
  fail_file(path, "not a prt file (unknown magic)");
}

}  // namespace

void add_info_command(CLI::App& app) {
  auto path = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("info", "Print the header of a prt file (.prt transfer, SH lighting .json)");
  cmd->add_option("FILE", *path, "File to describe")->required();
  cmd->callback([path] { run_info(*path); });
}

}  // namespace prt::cli
