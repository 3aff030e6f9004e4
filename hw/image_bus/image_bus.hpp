// The image bus (s2, fig. 1): NCs write runs of finished pixels to the data
// collector over one shared bus.
//
// Arbitration, documented in docs/timing.md: when the bus is free, the
// arbiter takes every request made up to that instant and grants the NC that
// follows the last granted one in round-robin order (NC index 1..N cyclic).
// A grant costs image_bus_arbitration_ns; then the run occupies the bus for
// the longer of its transfer time (header + 3 bytes per pixel at
// image_bus_bytes_per_s) and the DC's handling time (the DC accepts a run at
// the pace it writes the FM). The requesting NC's b_transport returns when
// its run has been taken.
//
// Request order decides the grant, so b_transport first synchronises
// (wait(delay)): the bus is the one place where an NC gives up its temporal
// decoupling. Payload: TLM_WRITE_COMMAND, data = encode_run(...).
// Binding: NC k (k = 1..N, in order) binds nc.nc2bus_pixels -> bus.nc2bus_pixels.
#pragma once

#include <deque>
#include <systemc>
#include <tlm>
#include <tlm_utils/multi_passthrough_target_socket.h>
#include <tlm_utils/simple_initiator_socket.h>
#include <vector>

#include "pixel_run.hpp"
#include "timing_params.hpp"

namespace mc1 {

class ImageBus : public sc_core::sc_module {
 public:
  tlm_utils::multi_passthrough_target_socket<ImageBus> nc2bus_pixels;
  tlm_utils::simple_initiator_socket<ImageBus> bus2dc;

  struct Grant {
    unsigned nc = 0;  // 1..N
    sc_core::sc_time requested, granted, released;
    std::size_t bytes = 0;
  };
  struct Stats {
    std::uint64_t runs = 0, bytes = 0, pixels = 0;
    sc_core::sc_time busy, waiting;  // bus occupied; NCs waiting for a grant
  };

  ImageBus(sc_core::sc_module_name name, const TimingParams& t);
  const std::vector<Grant>& grants() const { return grants_; }
  const Stats& stats() const { return stats_; }
  void keep_grant_log(bool on) { log_ = on; }

 private:
  struct Request {
    unsigned nc;
    sc_core::sc_time requested;
    tlm::tlm_generic_payload* payload;
    sc_core::sc_event done;
  };
  void b_transport(int index, tlm::tlm_generic_payload& p, sc_core::sc_time& delay);
  void arbiter();
  Request* pick(const sc_core::sc_time& decided);

  TimingParams t_;
  std::deque<Request*> pending_;
  sc_core::sc_event request_ev_;
  unsigned last_nc_ = 0;
  std::vector<Grant> grants_;
  bool log_ = true;
  Stats stats_;
};

}  // namespace mc1
