// The RC's dispatcher (s4): which piece of work goes to which NC, when a
// piece is overdue, and what happens to a lost NC's pieces. Plain C++: the
// RC's processor (its clock, its work, its sends) is an RcPort, so the
// dispatcher runs as well under SystemC (RootComputer over RcTransport) as
// under a test's hand-moved clock. docs/platform.md "The RC's protocol",
// "The rendered frame" (Faults).
//
// Each NC is in one NcState; every change goes through NcStates::to, which
// refuses a transition the RC never makes.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "hdlc_link.hpp"
#include "rc_protocol.hpp"
#include "timing_params.hpp"

namespace mc1::rc {

// Step 3's assignment of blocks to NCs.
enum class Schedule { Lpt, Fifo, Static };
const char* schedule_name(Schedule s);
// "lpt", "fifo", "static"; nullopt otherwise.
std::optional<Schedule> parse_schedule(const std::string& s);

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

// Where a piece of work stands.
struct Progress {
  std::uint32_t blocks_done = 0, blocks = 0;
  Picos time = 0;
};

struct DispatchStats {
  Picos last_completion = 0;
  Picos lists_done = 0;              // step 2: the last block list arrived (0: no step 2)
  std::uint64_t sort_compares = 0;   // the load sort of step 3
  std::uint64_t late_reports = 0;    // reports of pieces already done (ignored)
  std::uint64_t reassigned = 0;      // pieces handed out again after a timeout or link-down
  std::uint64_t revived = 0;         // NCs taken as dead that reported after all
};

// Where an NC stands with the RC.
enum class NcState : std::uint8_t {
  Starting,  // has not asked yet (download, step 1)
  Working,   // holds a piece of work, or has just reported one and waits for the answer
  Parked,    // asked while nothing was ready but pieces were out: waits for one to come back
  Finished,  // got Finish
  Dead,      // taken as dead (missed a deadline, or never asked); revived if it reports
  Lost,      // its link went down: dead for good
};
const char* nc_state_name(NcState s);
bool transition_allowed(NcState from, NcState to);

// The state of NCs 1..N, changed only by to().
class NcStates {
 public:
  explicit NcStates(unsigned nc_count) : s_(nc_count + 1, NcState::Starting) {}
  unsigned size() const { return static_cast<unsigned>(s_.size() - 1); }
  NcState operator[](unsigned nc) const { return s_.at(nc); }
  // Throws std::logic_error naming the NC and both states on a transition
  // transition_allowed refuses.
  void to(unsigned nc, NcState next);
  unsigned count(NcState s) const;
  // Dead or lost: its pieces are not waited for.
  bool taken_as_dead(unsigned nc) const;

 private:
  std::vector<NcState> s_;  // index = NC id; [0] unused
};

// What the dispatcher needs of the RC's processor.
class RcPort {
 public:
  virtual ~RcPort() = default;
  virtual Picos now() const = 0;                       // the processor's local time
  virtual void work(std::uint64_t mpu_cycles) = 0;     // the processor is busy
  virtual void send(unsigned nc, const Bytes& msg) = 0;  // post a message to NC nc
};

class Dispatcher {
 public:
  // Throws std::invalid_argument on a plan that does not fit together.
  Dispatcher(const TimingParams& t, unsigned nc_count, FramePlan plan, RcPort& port);

  // Called at every block completion.
  void on_progress(std::function<void(const Progress&)> f) { progress_ = std::move(f); }

  // While the frame runs: NC nc's Request or Lists (answered at once, or
  // the NC is parked); its link went down; deadlines passed by now; parked
  // NCs served if something came back.
  void on_message(unsigned nc, const Bytes& msg);
  void on_link_down(unsigned nc, hdlc::LinkDownReason why, Picos declared);
  void expire();
  void serve_parked();
  // After the frame: an NC taken as dead asks after all; true if it was
  // told Finish.
  bool on_message_after_frame(unsigned nc, const Bytes& msg);

  // Every block done and every NC finished or taken as dead.
  bool frame_complete() const;
  // Throws std::runtime_error when work is left that no NC can ever take.
  void check_progress_possible() const;
  // The nearest deadline to wait for (nullopt: wait for a message).
  std::optional<Picos> next_deadline() const;

  const NcStates& states() const { return states_; }
  const std::vector<Dispatch>& dispatches() const { return dispatches_; }
  const std::vector<Completion>& completions() const { return completions_; }
  const std::vector<Timeout>& timeouts() const { return timeouts_; }
  const std::vector<LinkDown>& link_downs() const { return link_downs_; }
  const DispatchStats& stats() const { return stats_; }
  // The order in which blocks are handed out (step 3).
  const std::vector<Block>& order() const { return order_; }
  // Step 2's block lists by block id (empty without step 2).
  const std::vector<BlockListMsg>& block_lists() const { return lists_; }
  std::string status() const;  // blocks done, NCs finished and dead (for errors)

 private:
  struct Piece {
    unsigned owner = 0;  // NC working on it, 0 = none
    bool done = false;
    Picos deadline = 0;
  };

  void check_plan() const;
  void start_lists_phase();
  void make_order(const std::vector<std::uint32_t>& load, bool charge);
  void start_step3();
  Picos block_timeout(std::uint64_t pixels, std::uint64_t work) const;
  std::uint64_t block_work(std::uint32_t block) const;
  Picos list_job_timeout(std::uint64_t blocks) const;

  void report_block(unsigned nc, std::uint32_t block);
  void report_lists(unsigned nc, const ListsMsg& m);
  void check_lists(unsigned nc, const ListsMsg& m, const std::vector<std::uint32_t>& ids) const;
  void serve(unsigned nc);  // answer NC's request now, or park it
  void hand_out_job(unsigned nc);
  void hand_out_block(unsigned nc, std::size_t rank);
  void finish(unsigned nc);
  bool waits_for_pieces_out() const { return plan_.fault_tolerant || !link_downs_.empty(); }
  std::optional<std::size_t> next_rank(unsigned nc) const;
  bool all_blocks_done() const { return blocks_done_ == order_.size(); }

  std::optional<Timeout> overdue(unsigned nc, Picos t) const;
  void expire_stragglers(Picos t);
  std::optional<Picos> straggler_deadline() const;
  std::uint32_t take_back(unsigned nc);
  void release_share(unsigned nc);
  void requeue_block(std::uint32_t block);

  TimingParams t_;
  unsigned nc_count_;
  FramePlan plan_;
  RcPort& port_;
  std::function<void(const Progress&)> progress_;

  NcStates states_;
  std::vector<Block> order_;
  std::vector<std::size_t> rank_of_;  // block id -> index in order_
  bool lists_phase_ = false;
  std::vector<Piece> jobs_, blocks_;          // step 2 list jobs; blocks by id
  std::set<std::uint32_t> jobs_ready_;
  std::set<std::size_t> ready_;               // ranks (lpt, fifo; static: a dead NC's share)
  std::vector<std::set<std::size_t>> own_;    // static: per NC (index = NC id)
  std::size_t blocks_done_ = 0;
  Picos all_done_at_ = 0;  // the last block was reported
  std::vector<BlockListMsg> lists_;

  std::vector<Dispatch> dispatches_;
  std::vector<Completion> completions_;
  std::vector<Timeout> timeouts_;
  std::vector<LinkDown> link_downs_;
  DispatchStats stats_;
};

}  // namespace mc1::rc
