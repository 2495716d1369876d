// The transfer passes' interface (transfer_pass.h) and the list of passes.
#include "render/transfer_pass.h"

#include <cstdio>

#include "core/error.h"

// The transfer kinds the renderer draws, one line each: PASS(name) for make_<name>_pass (pass_<name>.cpp).
// make_pass asks them in this order and takes the first that accepts the transfer.
#define PRT_RENDER_PASSES(PASS) \
  PASS(lightmap_cpca)           \
  PASS(cpca)                    \
  PASS(lightmap)                \
  PASS(glossy)                  \
  PASS(diffuse)

namespace prt::render {

#define PRT_DECLARE_PASS(name) std::unique_ptr<TransferPass> make_##name##_pass(FrameCore& core, const PassInput& input);
PRT_RENDER_PASSES(PRT_DECLARE_PASS)
#undef PRT_DECLARE_PASS

TransferPass::TransferPass(const std::string& origin, transfer::Kind kind) {
  sun_surface_.origin = origin;
  sun_surface_.shadows = kind != transfer::Kind::unshadowed;
}

void TransferPass::set_brdf(const brdf::BrdfMatrix&) { fail(std::string("renderer: a ") + name() + " pass takes no BRDF matrix"); }

void TransferPass::set_brdf_table(const std::vector<brdf::BrdfMatrix>&, const std::vector<std::uint32_t>&) {
  fail(std::string("renderer: a ") + name() + " pass takes one BRDF, not one per vertex");
}

void TransferPass::prepare_sun(FrameCore&, const Frame&) {}

void TransferPass::warn_no_bounce(const char* what) {
  if (sun_surface_.warned) return;
  std::fprintf(stderr, "prt: %s: no bounce-only section%s: the discs' interreflected light is left out; re-bake for it\n",
               sun_surface_.origin.c_str(), what);
  sun_surface_.warned = true;
}

void check_vertex_count(const FrameCore& core, const transfer::Header& header, const std::string& origin, const char* what) {
  if (header.vertex_count != core.vertex_count)
    fail_file(origin, std::string(what) + " has " + std::to_string(header.vertex_count) + " vertices, the mesh " +
                          std::to_string(core.vertex_count));
}

std::unique_ptr<TransferPass> make_pass(FrameCore& core, const PassInput& input) {
  if (!core.has_mesh) fail("renderer: set a mesh before its transfer");
  using Factory = std::unique_ptr<TransferPass> (*)(FrameCore&, const PassInput&);
#define PRT_LIST_PASS(name) &make_##name##_pass,
  const Factory factories[] = {PRT_RENDER_PASSES(PRT_LIST_PASS)};
#undef PRT_LIST_PASS
  for (const Factory factory : factories)
    if (std::unique_ptr<TransferPass> pass = factory(core, input)) return pass;
  fail_file(input.origin, std::string("the renderer has no pass for ") + transfer::kind_name(input.transfer.header.kind) + " transfer");
}

}  // namespace prt::render
