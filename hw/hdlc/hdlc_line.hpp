// The HDLC lines as a loosely-timed TLM-2.0 channel (s2: RC <-> NCs, 4 Mbps).
//
// A generic payload is one message: TLM_WRITE_COMMAND, data = the bytes,
// address = the destination link address (NC id 1..254 or 0xFF broadcast from
// the RC; 0 from an NC). b_transport runs the bit-level go-back-N network
// (hdlc_link.hpp) from the caller's local time (sc_time_stamp() + delay) until
// the message is acknowledged by every destination and returns with delay
// advanced to that moment: the wire time of its frames, retransmissions and
// acknowledgements. Each destination gets the message through its own target
// socket with delay = the moment its last frame's closing flag arrived; in
// messages to the RC the address is the sending NC's id. A message whose link
// goes down (retry limit N2, docs/hdlc.md) ends with
// TLM_GENERIC_ERROR_RESPONSE. No polling: the line does not supervise().
//
// Initiators use temporal decoupling (tlm_utils::tlm_quantumkeeper). The
// network's clock only moves forward: a message whose local time is earlier
// than the network's (an initiator lagging inside its quantum) starts at the
// network's time.
//
// Binding: rc.rc2nc_hdlc -> line.rc2nc_hdlc; line.hdlc2rc -> rc's target;
// for k = 1..N in order, nc[k].nc2rc_hdlc -> line.nc2rc_hdlc and
// line.hdlc2nc -> nc[k]'s target. Socket index k-1 is NC k.
#pragma once

#include <systemc>
#include <tlm>
#include <tlm_utils/multi_passthrough_initiator_socket.h>
#include <tlm_utils/multi_passthrough_target_socket.h>
#include <tlm_utils/simple_initiator_socket.h>
#include <tlm_utils/simple_target_socket.h>

#include "hdlc_link.hpp"
#include "sc_time_conv.hpp"
#include "timing_params.hpp"

namespace mc1::hdlc {

class HdlcLine : public sc_core::sc_module {
 public:
  tlm_utils::simple_target_socket<HdlcLine> rc2nc_hdlc;
  tlm_utils::multi_passthrough_target_socket<HdlcLine> nc2rc_hdlc;
  tlm_utils::multi_passthrough_initiator_socket<HdlcLine> hdlc2nc;
  tlm_utils::simple_initiator_socket<HdlcLine> hdlc2rc;

  HdlcLine(sc_core::sc_module_name name, const TimingParams& t, unsigned nc_count);

  Network& network() { return net_; }  // faults and statistics
  const Network& network() const { return net_; }

 private:
  void from_rc(tlm::tlm_generic_payload& p, sc_core::sc_time& delay);
  void from_nc(int index, tlm::tlm_generic_payload& p, sc_core::sc_time& delay);
  void carry(unsigned from, tlm::tlm_generic_payload& p, sc_core::sc_time& delay);
  void end_of_elaboration() override;

  Network net_;
};

}  // namespace mc1::hdlc
