// The data collector (s2, fig. 1): takes pixel runs off the image bus and
// writes them into the frame memory.
//
// bus2dc: TLM_WRITE_COMMAND carrying encode_run(...). The DC checks the run
// against the frame (x + count <= width, y < height; otherwise
// TLM_ADDRESS_ERROR_RESPONSE; a malformed run is TLM_GENERIC_ERROR_RESPONSE),
// spends dc_run_setup_ns on the header, and writes the pixels through dc2fm
// as one TLM write of 3 bytes per pixel at FM byte address 3 * (y * width + x).
// The returned delay is the DC's time plus the FM's.
#pragma once

#include <systemc>
#include <tlm>
#include <tlm_utils/simple_initiator_socket.h>
#include <tlm_utils/simple_target_socket.h>

#include "pixel_run.hpp"
#include "timing_params.hpp"

namespace mc1 {

class DataCollector : public sc_core::sc_module {
 public:
  tlm_utils::simple_target_socket<DataCollector> bus2dc;
  tlm_utils::simple_initiator_socket<DataCollector> dc2fm;

  struct Stats {
    std::uint64_t runs = 0, pixels = 0, rejected = 0;
  };

  DataCollector(sc_core::sc_module_name name, const TimingParams& t, unsigned width,
                unsigned height);
  const Stats& stats() const { return stats_; }

 private:
  void b_transport(tlm::tlm_generic_payload& p, sc_core::sc_time& delay);
  TimingParams t_;
  unsigned width_, height_;
  Stats stats_;
};

}  // namespace mc1
