// prt info: prints the header of a prt file: transfer .prt files, SH lighting .json files, probe files
// (.prtprobes) and BRDF matrix files (.bin and .json), recognised by their magic or JSON "format".
#include <cstdio>
#include <fstream>

#include <nlohmann/json.hpp>

#include "brdf/brdf_file.h"
#include "cli/commands.h"
#include "compress/cprt_file.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "light/light_file.h"
#include "probes/probe_file.h"
#include "transfer/transfer_file.h"

namespace prt::cli {

namespace {

void print_probes(const std::string& path) {
  const probes::ProbeSet p = probes::read_probe_file(path);
  std::printf("%s: prt probe file\nbands: %d (%zu coefficients)\nprobes: %zu (%zu valid)\n", path.c_str(), p.bands,
              p.coefficient_count(), p.count(), p.valid_count());
  if (p.layout == probes::ProbeSet::Layout::grid)
    std::printf("layout: grid %d x %d x %d, bounds [%g, %g, %g] .. [%g, %g, %g]\n", p.grid.counts[0], p.grid.counts[1],
                p.grid.counts[2], p.grid.lo.x, p.grid.lo.y, p.grid.lo.z, p.grid.hi.x, p.grid.hi.y, p.grid.hi.z);
  else
    std::printf("layout: points\n");
  std::printf("sky L00 (r,g,b): %.6g %.6g %.6g\n", p.sky.values[0].r, p.sky.values[0].g, p.sky.values[0].b);
  if (p.transfer_bands > 0)
    std::printf("transfer: %d bands, %d channel%s\n", p.transfer_bands, p.transfer_channels, p.transfer_channels == 1 ? "" : "s");
}

void print_brdf(const std::string& path) {
  const brdf::BrdfMatrix b = brdf::read_brdf_matrix(path);
  std::printf("%s: prt BRDF matrix\nbrdf: %s\nbands: %d (%d x %d per channel)\nchannels: %d\n", path.c_str(), b.spec.c_str(),
              b.bands, b.coefficients(), b.coefficients(), b.channels);
}

// The "format" member of a JSON file, or "" if it has none (or is not JSON).
std::string json_format(const std::string& path) {
  std::ifstream in = open_input(path);
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("format") || !j["format"].is_string()) return "";
  return j["format"].get<std::string>();
}

void run_info(const std::string& path) {
  std::ifstream in = open_input(path);
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
  if (head == "PRTPROBE") return print_probes(path);
  if (head == "PRTBRDF1") return print_brdf(path);
  if (!head.empty() && head[0] == '{') {
    if (json_format(path) == "prt-brdf-matrix") return print_brdf(path);
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
  CLI::App* cmd = app.add_subcommand(
      "info", "Print the header of a prt file (.prt transfer, SH lighting .json, .prtprobes, BRDF matrix .bin/.json)");
  cmd->add_option("FILE", *path, "File to describe")->required();
  cmd->callback([path] { run_info(*path); });
}

}  // namespace prt::cli
