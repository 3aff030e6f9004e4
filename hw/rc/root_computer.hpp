// The root computer (s2, s4): broadcasts the APU program and the frame set-up
// to every NC over the HDLC lines, then hands out blocks of the screen
// dynamically: each NC asks for a block when it is done with the previous
// one; the RC answers with the next block of its list (heaviest predicted
// load first, s4) or, when none is left, with Finish. docs/platform.md "The
// RC's protocol".
//
// Loosely timed: the RC's processor work is annotated from the timing table
// (one interrupt per message received, one list element per block taken,
// one word copy per 16 bits of a message) with a quantum keeper; sends are
// posted to the HDLC controller (rc2nc_hdlc, address = NC id or
// kHdlcBroadcast), received messages arrive through hdlc2rc (address = the
// sending NC).
#pragma once

#include <cstdint>
#include <systemc>
#include <tlm>
#include <tlm_utils/simple_initiator_socket.h>
#include <tlm_utils/simple_target_socket.h>
#include <tlm_utils/tlm_quantumkeeper.h>
#include <vector>

#include "hdlc_mailbox.hpp"
#include "rc_protocol.hpp"
#include "timing_params.hpp"

namespace mc1 {

// TLM address of a message to every NC (NC ids are 1..N).
constexpr sc_dt::uint64 kHdlcBroadcast = 0xFFFFFFFFu;

namespace rc {

struct Dispatch {
  Picos time = 0;       // the RC posted the message
  unsigned nc = 0;
  std::uint32_t block = kNoBlock;  // kNoBlock: Finish
};

struct Completion {
  Picos time = 0;  // the RC learned it (the NC's next request arrived)
  unsigned nc = 0;
  std::uint32_t block = 0;
};

struct Receipt {
  Picos arrived = 0;  // the message's last frame closed (within one pump step)
  Picos taken = 0;    // the RC's processor took it
  unsigned nc = 0;
};

struct RcStats {
  std::uint64_t messages_sent = 0, messages_received = 0, bytes_sent = 0, bytes_received = 0;
  Picos busy = 0;          // processor time annotated
  Picos setup_done = 0;    // program and set-up posted
  Picos last_completion = 0;
};

}  // namespace rc

class RootComputer : public sc_core::sc_module {
 public:
  tlm_utils::simple_initiator_socket<RootComputer> rc2nc_hdlc;
  tlm_utils::simple_target_socket<RootComputer> hdlc2rc;

  // `blocks` in any order, `load` their predicted loads (empty: all equal);
  // the RC hands them out heaviest first, ties in list order.
  RootComputer(sc_core::sc_module_name name, const TimingParams& t, unsigned nc_count,
               std::vector<apu::Encoded> program, rc::SetupMsg setup, std::vector<rc::Block> blocks,
               std::vector<std::uint32_t> load = {});

  const std::vector<rc::Dispatch>& dispatches() const { return dispatches_; }
  const std::vector<rc::Completion>& completions() const { return completions_; }
  const std::vector<rc::Receipt>& receipts() const { return receipts_; }  // every message, in order taken
  const rc::RcStats& stats() const { return stats_; }
  bool done() const { return done_; }  // every NC got Finish
  // The order in which blocks are handed out.
  const std::vector<rc::Block>& schedule() const { return order_; }

 private:
  void run();
  void b_transport(tlm::tlm_generic_payload& p, sc_core::sc_time& delay);
  void work(std::uint64_t mpu_cycles);
  void post(sc_dt::uint64 address, const rc::Bytes& msg);
  HdlcMailbox::Message receive();
  Picos now() const;

  TimingParams t_;
  unsigned nc_count_;
  std::vector<apu::Encoded> program_;
  rc::SetupMsg setup_;
  std::vector<rc::Block> order_;
  HdlcMailbox inbox_;
  tlm_utils::tlm_quantumkeeper qk_;
  std::vector<rc::Dispatch> dispatches_;
  std::vector<rc::Completion> completions_;
  std::vector<rc::Receipt> receipts_;
  rc::RcStats stats_;
  bool done_ = false;
};

}  // namespace mc1
