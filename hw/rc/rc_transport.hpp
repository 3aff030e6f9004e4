// The RC's side of its HDLC lines (s2, s4) and the clock of its processor.
// Sends are posted to the HDLC controller (rc2nc_hdlc, address = NC id or
// kHdlcBroadcast); received messages and the controller's link-down reports
// arrive through hdlc2rc (address = the sending NC) into a mailbox the RC's
// thread takes from; link supervision is switched on and off with an
// HdlcLinkEvent (docs/hdlc.md "Supervision").
//
// Loosely timed: the processor's work (one interrupt per message received,
// one word copy per 16 bits of a message sent or received, and what the
// dispatcher charges) is annotated from the timing table with a quantum
// keeper.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <systemc>
#include <tlm>
#include <tlm_utils/tlm_quantumkeeper.h>
#include <vector>

#include "hdlc_link_event.hpp"
#include "hdlc_mailbox.hpp"
#include "rc_dispatcher.hpp"
#include "rc_protocol.hpp"
#include "timing_params.hpp"

namespace mc1 {

namespace rc {

struct Receipt {
  Picos arrived = 0;  // the message's last frame closed (within one pump step)
  Picos taken = 0;    // the RC's processor took it
  unsigned nc = 0;
};

struct TransportStats {
  std::uint64_t messages_sent = 0, messages_received = 0, bytes_sent = 0, bytes_received = 0;
  Picos busy = 0;  // processor time annotated
};

class RcTransport final : public RcPort {
 public:
  // `owner` names the module in error reports; `rc2nc` is its socket to the
  // HDLC controller (bound before the simulation starts).
  RcTransport(std::string owner, const TimingParams& t, unsigned nc_count, tlm::tlm_initiator_socket<>& rc2nc);

  // hdlc2rc's b_transport: a message from NC <address>, or the controller's
  // report that its link is down.
  void deliver(tlm::tlm_generic_payload& p, sc_core::sc_time& delay);

  Picos now() const override;
  void work(std::uint64_t mpu_cycles) override;
  void send(unsigned nc, const Bytes& msg) override { post(nc, msg); }
  void post(sc_dt::uint64 address, const Bytes& msg);
  // Tells the HDLC controller to poll idle links from now on, or to stop.
  void supervise_links(bool on);
  // The next message or link-down report; nullopt when `deadline` (absolute)
  // passes first. Blocks the calling SystemC thread.
  std::optional<HdlcMailbox::Message> receive(std::optional<Picos> deadline);
  void sync() { qk_.sync(); }

  const std::vector<Receipt>& receipts() const { return receipts_; }  // every message, in order taken
  const TransportStats& stats() const { return stats_; }

 private:
  sc_core::sc_time to_controller(tlm::tlm_generic_payload& p);

  std::string owner_;
  TimingParams t_;
  unsigned nc_count_;
  tlm::tlm_initiator_socket<>& rc2nc_;
  HdlcMailbox inbox_;
  tlm_utils::tlm_quantumkeeper qk_;
  std::vector<Receipt> receipts_;
  TransportStats stats_;
};

}  // namespace rc
}  // namespace mc1
