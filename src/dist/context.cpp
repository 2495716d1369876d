// The parts of Context that do not depend on the backend (backend_mpi.cpp or backend_local.cpp).
#include "dist/context.h"

namespace prt::dist {

Context& Context::world() {
  static Context* world = [] {
    auto* c = new Context();  // never destroyed: finalize() is explicit, and exit paths may run late
    c->init_from_environment();
    return c;
  }();
  return *world;
}

const Context& Context::single() {
  static const Context single;
  return single;
}

// Calling world() here is cheap without mpirun (no MPI then); under mpirun it has been called already.
int finish(int status) {
  Context::world().finalize();
  return status;
}

int finish_after_error(int status, bool collective) {
  Context& world = Context::world();
  if (world.size() > 1 && !collective) world.abort_job(status);
  world.finalize();
  return status;
}

}  // namespace prt::dist
