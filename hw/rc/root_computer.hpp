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
// Loosely timed: the RC's processor work is annotated from the timing table
// (one interrupt per message received, one list element per piece taken,
// one word copy per 16 bits of a message, the sort of the block list) with a
// quantum keeper; sends are posted to the HDLC controller (rc2nc_hdlc,
// address = NC id or kHdlcBroadcast), received messages arrive through
// hdlc2rc (address = the sending NC).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <systemc>
#include <tlm>
#include <tlm_utils/simple_initiator_socket.h>
#include <tlm_utils/simple_target_socket.h>
#include <tlm_utils/tlm_quantumkeeper.h>
#include <vector>

#include "hdlc_link_event.hpp"
#include "hdlc_mailbox.hpp"
#include "rc_protocol.hpp"
#include "timing_params.hpp"

namespace mc1 {

namespace rc {

// Step 3's assignment of blocks to NCs.
enum class Schedule { Lpt, Fifo, Static };
const char* schedule_name(Schedule s);
// "lpt", "fifo", "static"; nullopt otherwise.
std::optional<Schedule> parse_schedule(const std::string& s);

struct Dispatch {
  Picos time = 0;       // the RC posted the message
  unsigned nc = 0;
  std::uint32_t block = kNoBlock;  // kNoBlock: Finish
  bool list_job = false;           // a step-2 list job; `block` is the job's first block
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

// A deadline the RC saw pass: the NC is taken as dead from then on.
struct Timeout {
  Picos time = 0;
  unsigned nc = 0;
  std::uint32_t block = kNoBlock;  // the piece whose deadline passed
  bool list_job = false;
  std::uint32_t requeued = 0;      // unfinished pieces of that NC handed back to the queue
};

// The HDLC controller gave NC `nc`'s link up: the NC is lost for the frame.
struct LinkDown {
  Picos time = 0;   // the controller declared it
  Picos taken = 0;  // the RC's processor took the report and acted
  unsigned nc = 0;
  hdlc::LinkDownReason reason = hdlc::LinkDownReason::RetryLimit;
  std::uint32_t requeued = 0;  // unfinished pieces of that NC handed back to the queue
};

struct RcStats {
  std::uint64_t messages_sent = 0, messages_received = 0, bytes_sent = 0, bytes_received = 0;
  Picos busy = 0;          // processor time annotated
  Picos setup_done = 0;    // downloads and set-up posted
  Picos last_completion = 0;
  Picos done_at = 0;       // every block done and every live NC told (or taken as dead)
  std::uint64_t download_bytes = 0;  // broadcast before the first piece of work
  Picos lists_done = 0;              // step 2: the last block list arrived (0: no step 2)
  std::uint64_t sort_compares = 0;   // the load sort of step 3
  std::uint64_t late_reports = 0;    // reports of pieces already done (ignored)
  std::uint64_t reassigned = 0;      // pieces handed out again after a timeout
  std::uint64_t revived = 0;         // NCs taken as dead that reported after all
};

// Where a piece of work stands.
struct Progress {
  std::uint32_t blocks_done = 0, blocks = 0;
  Picos time = 0;
};

// What the RC does in one frame.
struct FramePlan {
  std::vector<Bytes> downloads;     // broadcast first, in order (program, data, set-up)
  std::vector<Block> blocks;        // the screen split; ids 0..n-1 in screen order
  std::vector<std::uint32_t> load;  // predicted loads when known up front (empty: all equal)
  bool block_lists = false;         // step 2: NCs build the block lists (ListJob / Lists)
  std::uint32_t list_jobs = 0;      // number of list jobs (0: one per NC)
  Schedule schedule = Schedule::Lpt;
  bool fault_tolerant = false;      // deadlines, reassignment, parking
  // Per object (step 2's lists name objects): its work per pixel for the
  // deadline, its primitives, 4x if it reflects or refracts. Empty: a
  // block's work is its predicted load.
  std::vector<std::uint32_t> object_work;
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
  void on_progress(std::function<void(const rc::Progress&)> f) { progress_ = std::move(f); }

  const std::vector<rc::Dispatch>& dispatches() const { return dispatches_; }
  const std::vector<rc::Completion>& completions() const { return completions_; }
  const std::vector<rc::Receipt>& receipts() const { return receipts_; }  // every message, in order taken
  const std::vector<rc::Timeout>& timeouts() const { return timeouts_; }
  const std::vector<rc::LinkDown>& link_downs() const { return link_downs_; }
  const rc::RcStats& stats() const { return stats_; }
  bool done() const { return done_; }  // every block done, every live NC got Finish
  std::string status() const;          // blocks done, NCs finished and dead (for errors)
  // The order in which blocks are handed out (step 3; after step 2 when the
  // NCs build the block lists).
  const std::vector<rc::Block>& schedule() const { return order_; }
  // Step 2's block lists by block id (empty without step 2).
  const std::vector<rc::BlockListMsg>& block_lists() const { return lists_; }
  // Deadline of a block of `pixels` pixels and `work` per pixel (the
  // weighted primitives of its list, or its load), and of a list job of
  // `blocks` blocks, from the piece's dispatch (docs/timing.md).
  Picos block_timeout(std::uint64_t pixels, std::uint64_t work) const;
  std::uint64_t block_work(std::uint32_t block) const;
  Picos list_job_timeout(std::uint64_t blocks) const;

 private:
  struct Piece {
    int owner = 0;  // NC working on it, 0 = none
    bool done = false;
    Picos deadline = 0;
  };

  void run();
  void b_transport(tlm::tlm_generic_payload& p, sc_core::sc_time& delay);
  void work(std::uint64_t mpu_cycles);
  void post(sc_dt::uint64 address, const rc::Bytes& msg);
  void supervise_links(bool on);
  std::optional<HdlcMailbox::Message> receive(std::optional<Picos> deadline);
  Picos now() const;

  void make_order(const std::vector<std::uint32_t>& load, bool charge);
  void handle(const HdlcMailbox::Message& m);
  void link_down(const HdlcMailbox::Message& m);
  std::uint32_t take_back(unsigned nc);
  void check_progress_possible() const;
  bool waits_for_pieces_out() const { return plan_.fault_tolerant || !link_downs_.empty(); }
  void report_block(unsigned nc, std::uint32_t block);
  void report_lists(unsigned nc, const rc::ListsMsg& lists);
  void serve(unsigned nc);         // answer NC's request now, or park it
  void serve_parked();
  std::optional<std::size_t> next_rank(unsigned nc) const;
  void requeue_block(std::uint32_t block);
  void finish(unsigned nc);
  std::optional<Picos> next_deadline() const;
  std::optional<Picos> straggler_deadline() const;
  void expire(Picos t);
  bool all_blocks_done() const { return blocks_done_ == order_.size(); }
  bool frame_complete() const;

  TimingParams t_;
  unsigned nc_count_;
  rc::FramePlan plan_;
  std::vector<rc::Block> order_;
  std::vector<std::size_t> rank_of_;  // block id -> index in order_
  HdlcMailbox inbox_;
  tlm_utils::tlm_quantumkeeper qk_;
  std::function<void(const rc::Progress&)> progress_;

  bool lists_phase_ = false;
  std::vector<Piece> jobs_, blocks_;     // step 2 list jobs; blocks by id
  std::set<std::uint32_t> jobs_ready_;
  std::set<std::size_t> ready_;                    // ranks (lpt, fifo)
  std::vector<std::set<std::size_t>> own_;         // static: per NC (index = NC id)
  std::size_t blocks_done_ = 0;
  std::vector<bool> dead_, parked_, finished_, asked_;
  std::vector<bool> lost_;  // its link went down: dead for good
  Picos all_done_at_ = 0;  // the last block was reported
  std::vector<rc::BlockListMsg> lists_;

  std::vector<rc::Dispatch> dispatches_;
  std::vector<rc::Completion> completions_;
  std::vector<rc::Receipt> receipts_;
  std::vector<rc::Timeout> timeouts_;
  std::vector<rc::LinkDown> link_downs_;
  rc::RcStats stats_;
  bool done_ = false;
};

}  // namespace mc1
