// Sits between the image bus and the DC (bus.bus2dc -> monitor -> dc): the
// bus calls the DC at the instant it grants a run, so here the grant becomes
// visible. It stamps the grant time into the sender's NcIdExtension (the NC's
// activity chart splits waiting from sending with it) and drives the traced
// signals image_bus_grant / image_bus_owner (NC id, 0 = none) for the
// run's bus time: the longer of its transfer and the DC's handling, as
// ImageBus holds it (docs/timing.md).
//
// It is also the DC's write-once filter: it keeps a map of the FM pixels
// written so far, and a run whose pixels are all written already is a late
// duplicate (a block the RC handed out again after a deadline, rendered by
// the new owner after the first had sent some rows) and is dropped after
// its transfer: every FM pixel is written once. Both copies are equal (the
// image does not depend on the NC), so dropping either would do.
#pragma once

#include <cstdint>
#include <vector>

#include <systemc>
#include <tlm>
#include <tlm_utils/simple_initiator_socket.h>
#include <tlm_utils/simple_target_socket.h>

#include "timing_params.hpp"

namespace mc1 {

class ImageBusMonitor : public sc_core::sc_module {
 public:
  tlm_utils::simple_target_socket<ImageBusMonitor> bus2dc;
  tlm_utils::simple_initiator_socket<ImageBusMonitor> mon2dc;

  ImageBusMonitor(sc_core::sc_module_name name, const TimingParams& t, unsigned width, unsigned height);
  void trace(sc_core::sc_trace_file* tf);
  std::uint64_t duplicate_runs() const { return duplicate_runs_; }
  std::uint64_t duplicate_pixels() const { return duplicate_pixels_; }

 private:
  void b_transport(tlm::tlm_generic_payload& p, sc_core::sc_time& delay);
  void release();

  TimingParams t_;
  sc_core::sc_signal<bool, sc_core::SC_MANY_WRITERS> grant_;
  sc_core::sc_signal<unsigned, sc_core::SC_MANY_WRITERS> owner_;
  sc_core::sc_event release_ev_;
  sc_core::sc_time release_at_;
  unsigned width_, height_;
  std::vector<bool> written_;
  std::uint64_t duplicate_runs_ = 0, duplicate_pixels_ = 0;
};

}  // namespace mc1
