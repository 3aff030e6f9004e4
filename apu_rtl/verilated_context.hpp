// The Verilator context every verilated model of the tree is built in
// (hw/apu_rtl_engine, tests/): one simulation thread, the caller's.
//
// Verilator 5 gives a context a pool of hardware_concurrency() - 1 worker
// threads, made when its first model is added, unless threads() was set
// first. Our models are verilated without --threads, so those workers
// would only wait: 63 idle threads a model on a 64-core host, and a thread
// the host will not start (a process limit) would throw std::system_error
// from the model's constructor, on whichever thread builds it (an
// fp24-regress worker, an APU engine's). tests/thread_limit_test.sh runs
// fp24-regress under such a limit.
#pragma once

#include <memory>

#include "verilated.h"

namespace mc1::rtl {

// A context whose models run on the calling thread only, every register and
// word 0 at power-on (Verilator's randReset(0): the ISA's power-on state).
inline std::unique_ptr<VerilatedContext> new_context() {
  auto ctx = std::make_unique<VerilatedContext>();
  ctx->threads(1);
  ctx->randReset(0);
  return ctx;
}

}  // namespace mc1::rtl
