// The root computer (s2, s4): broadcasts the frame's programs and data to
// every NC over the HDLC lines, then hands out work dynamically: each NC asks
// when it is done with the previous piece; the RC answers with the next piece
// by its schedule or, when none is left, with Finish. docs/platform.md "The
// RC's protocol".
//
// Two frames: the diagnostic frame (blocks straight away) and the rendered
// frame of fig. 3, whose step 2 has the NCs build the block lists (list
// jobs) before step 3 hands the blocks out with their lists. Schedules
// (step 3): lpt = heaviest predicted load first (the paper's), fifo = screen
// order as NCs ask, static = block i to NC (i mod N) + 1.
//
// Fault tolerance: the RC's HDLC controller supervises every NC's link
// while the frame runs (docs/hdlc.md "Supervision": retry limit N2, polls of
// idle links) and reports a link that goes down; the NC is then lost for
// the frame at once: its unfinished pieces go back to the queue for the
// others (any frame). In the rendered frame every piece handed out also has
// a deadline (docs/timing.md "rc_timeout_*"), the last resort for an NC
// alive on its link but stuck: an NC that misses one is taken as dead, its
// pieces go back likewise, and an NC that asks while nothing is ready but
// pieces are still out waits (parked) until something comes back or the
// frame is complete (after a link-down, in any frame). A late report of a
// piece already done is ignored; an NC taken as dead by a deadline that
// reports after all was only slow: it gets work again (one whose link went
// down cannot). An NC that never asks at all is taken as dead
// rc_timeout_base_ns after the last block is done. Work left when every NC
// has finished or lost its link is an error: nothing waits forever.
//
// Two parts: rc::RcTransport (rc_transport.hpp) is the RC's side of the
// HDLC lines and its processor's clock; rc::Dispatcher (rc_dispatcher.hpp,
// plain C++) decides what each NC gets, with every NC in one rc::NcState.
// This module runs the frame: download, then messages to the dispatcher
// until the frame is complete.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <systemc>
#include <tlm>
#include <tlm_utils/simple_initiator_socket.h>
#include <tlm_utils/simple_target_socket.h>
#include <vector>

#include "hdlc_link_event.hpp"
#include "hdlc_mailbox.hpp"
#include "rc_protocol.hpp"
#include "rc_dispatcher.hpp"
#include "rc_transport.hpp"
#include "timing_params.hpp"

namespace mc1 {

namespace rc {

// Everything the RC counts: its HDLC side, its dispatcher, the frame.
struct RcStats : TransportStats, DispatchStats {
  Picos setup_done = 0;              // downloads and set-up posted
  Picos done_at = 0;                 // every block done and every live NC told (or taken as dead)
  std::uint64_t download_bytes = 0;  // broadcast before the first piece of work
};

}  // namespace rc

class RootComputer : public sc_core::sc_module {
 public:
  tlm_utils::simple_initiator_socket<RootComputer> rc2nc_hdlc;
  tlm_utils::simple_target_socket<RootComputer> hdlc2rc;

  // The diagnostic frame: broadcasts Program and Setup, then hands `blocks`
  // (any order) out heaviest `load` first (empty: all equal), ties in list
  // order; Finish as soon as nothing is left.
  RootComputer(sc_core::sc_module_name name, const TimingParams& t, unsigned nc_count,
               std::vector<apu::Encoded> program, rc::SetupMsg setup, std::vector<rc::Block> blocks,
               std::vector<std::uint32_t> load = {});
  RootComputer(sc_core::sc_module_name name, const TimingParams& t, unsigned nc_count, rc::FramePlan plan);

  // Called at every block completion (from the RC's thread).
  void on_progress(std::function<void(const rc::Progress&)> f) { dispatcher_.on_progress(std::move(f)); }

  const std::vector<rc::Dispatch>& dispatches() const { return dispatcher_.dispatches(); }
  const std::vector<rc::Completion>& completions() const { return dispatcher_.completions(); }
  // Every message, in order taken.
  const std::vector<rc::Receipt>& receipts() const { return transport_.receipts(); }
  const std::vector<rc::Timeout>& timeouts() const { return dispatcher_.timeouts(); }
  const std::vector<rc::LinkDown>& link_downs() const { return dispatcher_.link_downs(); }
  rc::RcStats stats() const;
  bool done() const { return done_; }  // every block done, every live NC got Finish
  // Blocks done, NCs finished and dead (for errors).
  std::string status() const { return dispatcher_.status(); }
  // The order in which blocks are handed out (step 3; after step 2 when the
  // NCs build the block lists).
  const std::vector<rc::Block>& schedule() const { return dispatcher_.order(); }
  // Step 2's block lists by block id (empty without step 2).
  const std::vector<rc::BlockListMsg>& block_lists() const { return dispatcher_.block_lists(); }

 private:
  void run();
  void b_transport(tlm::tlm_generic_payload& p, sc_core::sc_time& delay) { transport_.deliver(p, delay); }
  void download();
  void run_frame();
  void finish_stragglers();

  std::vector<rc::Bytes> downloads_;
  rc::RcTransport transport_;
  rc::Dispatcher dispatcher_;
  Picos setup_done_ = 0, done_at_ = 0;
  std::uint64_t download_bytes_ = 0;
  bool done_ = false;
};

}  // namespace mc1
