#include "node_computer.hpp"

#include <algorithm>
#include <chrono>
#if defined(__x86_64__) || defined(__i386__)
#include <x86intrin.h>
#endif
#include <stdexcept>
#include <string>

#include "apu_iss.hpp"
#include "sc_time_conv.hpp"
#include "sc_kernel.hpp"

namespace mc1::nc {
namespace {

// Host time of a stretch of APU clocking (the benchmark's split between the
// APU's work and SystemC's), read twice per APU run, some 10^5 times a
// frame: in the cheapest clock there is, the x86 time-stamp counter (a
// constant rate on the hosts this runs on; elsewhere steady_clock's count),
// turned into seconds once, when the NC closes the frame (seconds_per_tick).
std::uint64_t host_ticks() {
#if defined(__x86_64__) || defined(__i386__)
  return __rdtsc();
#else
  return static_cast<std::uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count());
#endif
}

// Both clocks at the first timed run (the rate's start).
struct RateStart {
  std::chrono::steady_clock::time_point t = std::chrono::steady_clock::now();
  std::uint64_t ticks = host_ticks();
};
const RateStart& rate_start() {
  static const RateStart start;
  return start;
}

// Seconds per tick, against steady_clock from the first timed run to now.
double seconds_per_tick() {
  const RateStart& start = rate_start();
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start.t).count();
  const std::uint64_t n = host_ticks() - start.ticks;
  return n > 0 ? s / static_cast<double>(n) : 0;
}

// Into `all`, and into `simulation` too on the simulation's own thread
// (not a pool worker's).
class HostTimer {
 public:
  HostTimer(std::uint64_t& all, std::uint64_t& simulation) : all_(all), simulation_(simulation), t0_(host_ticks()) {
    (void)rate_start();  // the rate's start, before the first run ends (the rate itself reads both clocks)
  }
  ~HostTimer() {
    const std::uint64_t t = host_ticks() - t0_;
    all_ += t;
    if (!ApuJob::on_worker()) simulation_ += t;
  }

 private:
  std::uint64_t& all_;
  std::uint64_t& simulation_;
  std::uint64_t t0_;
};

// Unwinds the firmware when the NC's processor stops (kill_at).
struct Killed {};

// Sets a flag for a scope.
struct FlagGuard {
  bool& flag;
  const bool was;
  explicit FlagGuard(bool& f) : flag(f), was(f) { flag = true; }
  ~FlagGuard() { flag = was; }
};

}  // namespace

const char* activity_name(Activity a) {
  switch (a) {
    case Activity::WaitRc: return "wait_rc";
    case Activity::Busy: return "busy";
    case Activity::WaitBus: return "wait_bus";
    case Activity::Idle: return "idle";
    case Activity::Dead: return "dead";
  }
  return "?";
}

NodeComputer::NodeComputer(sc_core::sc_module_name name, const TimingParams& t, unsigned id,
                           std::unique_ptr<apu::ApuEngine> engine, Firmware firmware)
    : sc_module(name),
      nc2rc_hdlc("nc2rc_hdlc"),
      hdlc2nc("hdlc2nc"),
      nc2bus_pixels("nc2bus_pixels"),
      t_(t),
      id_(id),
      engine_(std::move(engine)),
      driver_(*engine_),
      firmware_(std::move(firmware)),
      cycle_ps_(t.apu_cycle_ps()),
      bank_while_running_(engine_->mpu_bank_while_running()) {
  hdlc2nc.register_b_transport(this, &NodeComputer::b_transport);
  driver_.set_access_hook([this] { settle_apu(); });
  driver_.set_bank_hook([this] { touch_mpu_bank(); });
  driver_.set_hand_over_hook([this] { return defer_hand_over(); });
  SC_HAS_PROCESS(NodeComputer);
  SC_THREAD(run);
}

NodeComputer::~NodeComputer() {
  if (job_) job_->cancel();  // the simulation ended while the NC waited: no more of the run
  // The engine outlives mpu_ (members go in reverse order) and its trace's
  // last dump, in its destructor, would read it: no MPU side from here on.
  if (engine_) engine_->trace_mpu({});
}

// The APU run the MPU waits for, from apu_time_ on, clocked by the pool's
// threads. Meanwhile the NC waits in simulated time, each step only as far
// as the run is known to last (a step stays inside the run, the NC does
// nothing visible in it) and never up to the kill time: the other NCs run
// their firmware and hand their APU runs to the pool. Nothing simulated
// depends on the steps (nor on any synchronisation of the NC: see
// advance()), so the simulation is the same for any number of threads; the
// caller then advances to the run's end as without a pool.
std::uint64_t NodeComputer::run_on_pool(ApuJob::Stretch stretch) {
  job_ = (pool_ ? *pool_ : inline_).post(std::move(stretch));
  if (parallel()) qk_.sync();  // the other NCs first, while a worker takes the run
  const Picos start = apu_time_;
  // One thread: the run is over already (post() clocked it), nothing to
  // overlap. Else the NC steps as far as the run is known to last, at least
  // kPoolStepCycles at a time.
  for (std::uint64_t step = kPoolStepCycles; parallel();) {
    const std::uint64_t known = job_->known(step);
    const Picos target = start + known * cycle_ps_;
    if (known == 0 || target >= kill_at_) break;
    step = known + kPoolStepCycles;
    const Picos t = now();
    if (target <= t) continue;
    qk_.inc(to_sc_time(target - t));
    qk_.sync();
  }
  const std::shared_ptr<ApuJob> job = std::move(job_);
  return job->result();
}

Picos NodeComputer::now() const {
  return to_picos(sc_core::sc_time_stamp()) + to_picos(qk_.get_local_time());
}

void NodeComputer::mark(Activity a, Picos at) {
  at = std::max(at, since_);
  if (at > since_) {
    if (!spans_.empty() && spans_.back().what == current_ && spans_.back().block == span_block_ &&
        spans_.back().end == since_)
      spans_.back().end = at;  // same activity, same block: one span
    else
      spans_.push_back(Span{since_, at, current_, span_block_});
    since_ = at;
  }
  current_ = a;
  span_block_ = block_;
}

void NodeComputer::apu_stopped(Picos at) {
  if (!apu_open_) return;
  apu_spans_.push_back(ApuSpan{apu_begin_, at});
  stats_.apu_running += at - apu_begin_;
  apu_open_ = false;
}

void NodeComputer::check_fault() const {
  if (engine_->state() == apu::RunState::Faulted)
    throw std::runtime_error("NC " + std::to_string(id_) + ": APU fault " +
                             apu::fault_name(engine_->fault()) + " at cycle " +
                             std::to_string(engine_->cycle()));
}

void NodeComputer::catch_up() {
  settle_apu();
  catch_up_to(now());
}

// The MPU's work only moves the NC's time (advance): the APU's catch-up to
// it waits, in apu_due_ or as a job on the pool, until the APU is next
// looked at: here, through the driver's access hook or the NC's own calls.
// One catch-up to t2 clocks what catch-ups to t1 <= t2 and then t2 do.
void NodeComputer::settle_apu() {
  if (settling_ || ApuJob::in_job()) return;
  const FlagGuard guard(settling_);
  if (job_) join_job();  // an APU fault: the error, as from catch_up()
  if (apu_due_set_) {
    apu_due_set_ = false;
    catch_up_to(apu_due_);
  }
}

// The MPU reads or writes its data bank, no hand-over pending: the APU
// cannot swap the banks in what it is owed (apu_due_, a job on the pool), so
// it is not clocked for it, and a job goes on clocking it meanwhile where
// the engine allows.
void NodeComputer::touch_mpu_bank() {
  if (!job_ || bank_while_running_ || settling_ || ApuJob::in_job()) return;
  join_job();
}

// The catch-up job's end, and a data hand-over it was to make and did not
// (it ended, its due reached, before the hand-over was asked of it): made
// now, where the job would have made it (settling_: the driver's access
// hook, which run() calls, must not clock the APU past it first).
void NodeComputer::join_job() {
  // A catch-up job still running on a worker: the kernel runs the other NCs
  // first (they hand their APUs to the pool meanwhile), so that the job is
  // likely over when this NC goes on, instead of its waiting here.
  if (in_thread_ && !job_->over()) qk_.sync();
  const std::shared_ptr<ApuJob> job = std::move(job_);
  job->result();
  if (hand_over_due_.load(std::memory_order_acquire)) {
    const FlagGuard guard(settling_);
    catch_up_to(hand_over_at_);
    engine_->hand_over_data();
    hand_over_due_.store(false, std::memory_order_relaxed);
  }
}

// The MPU hands the APU a data bank while a catch-up job clocks the APU
// (a swap's wait, the next call through the access hook, waits for it
// anyway): instead of waiting for the job here, the job hands the bank over
// once the APU is where the MPU's time was at the call (apu_due_), before
// any later cycle, as the catch-up and hand-over here would; or, if the job
// ends first (it may have read its due just before), join_job() does.
bool NodeComputer::defer_hand_over() {
  if (!job_ || !bank_while_running_ || settling_ || ApuJob::in_job() || job_->over() ||
      hand_over_due_.load(std::memory_order_acquire))
    return false;
  hand_over_at_ = apu_due_;  // chase_due_ too: the job's catch-ups so far end there or before
  hand_over_due_.store(true, std::memory_order_release);
  return true;
}

void NodeComputer::catch_up_to(Picos t) {
  if (engine_->state() != apu::RunState::Running) {
    apu_stopped(apu_time_);
    apu_time_ = t;
    return;
  }
  if (!apu_open_) {
    apu_open_ = true;
    apu_begin_ = apu_time_;
  }
  if (t <= apu_time_) return;
  const std::uint64_t k = (t - apu_time_) / cycle_ps_;
  if (k == 0) return;
  std::uint64_t n = 0;
  engine_->set_time(apu_time_, cycle_ps_);
  {
    HostTimer timer(apu_host_ticks_, apu_host_sim_ticks_);
    n = driver_.run(k);
  }
  stats_.apu_cycles += n;
  apu_time_ += n * cycle_ps_;
  if (engine_->state() != apu::RunState::Running) {  // stopped inside the span (maybe in its last cycle)
    check_fault();
    // Let results of the HALT word's own ops land (docs/apu-isa.md, Clarification 7).
    apu::CycleRecord settle;
    for (int i = 0; i < apu::ApuDriver::kSettleCycles; ++i) engine_->step(settle);
    apu_stopped(apu_time_);
    apu_time_ = t;
  }
}

void NodeComputer::check_alive() {
  if (now() >= kill_at_) throw Killed{};
}

void NodeComputer::advance(Picos ps, Picos t) {
  if (t + ps >= kill_at_) {  // the processor stops inside this span
    qk_.inc(to_sc_time(kill_at_ > t ? kill_at_ - t : 0));
    catch_up();
    throw Killed{};
  }
  qk_.inc(to_sc_time(ps));
  apu_due_ = detail::sc_resolution_is_ps() ? t + ps : now();  // now(), without asking the kernel again
  apu_due_set_ = true;
  chase_due_.store(apu_due_, std::memory_order_release);
  // No simulated time depends on where the NC synchronises (the HDLC
  // channel delivers on its own time grid, the NC syncs before it looks at
  // its mailbox, the image bus waits out the request's time): it syncs
  // only so that, while its APU runs, the kernel runs the other NCs as a
  // worker clocks this one's catch-up. What the APU owes goes to the pool
  // once it owes kChaseCycles; the job chases the NC's time as it moves on
  // (chase_due_), and while it runs the NC goes on with its own work, and
  // syncs where it would wait for the job, if the job is not over by then
  // (join_job). A sync here too, after each post, cost the simulation's
  // thread a kernel round per catch-up job (some 10^5 a frame) and made
  // two threads 2.6 % slower (farm-bench, 15 pairs).
  // With no worker (one thread) nothing is posted and the NC does not
  // sync: the catch-up is clocked where the APU is next looked at, in one
  // piece.
  if (!parallel() || (job_ && !job_->over())) return;
  if (engine_->state() != apu::RunState::Running || apu_due_ <= apu_time_ ||
      (apu_due_ - apu_time_) / cycle_ps_ < kChaseCycles)
    return;
  if (job_) join_job();
  job_ = pool_->post([this](ApuJob&) -> std::optional<std::uint64_t> {
    // chase_due_ first: a due past hand_over_at_ comes with hand_over_due_ set.
    const Picos due = chase_due_.load(std::memory_order_acquire);
    const bool hand_over = hand_over_due_.load(std::memory_order_acquire);
    const Picos until = hand_over ? std::min(due, hand_over_at_) : due;
    catch_up_to(std::min(until, apu_time_ + kPoolStepCycles * cycle_ps_));
    if (hand_over && apu_time_ + cycle_ps_ > hand_over_at_) {  // clocked up to the hand-over's time
      engine_->hand_over_data();
      hand_over_due_.store(false, std::memory_order_relaxed);
    } else if (hand_over) {
      return std::nullopt;
    }
    if (engine_->state() != apu::RunState::Running || apu_time_ + cycle_ps_ > due) return 0;
    return std::nullopt;
  });
}

void NodeComputer::mpu_is(MpuDoing d, Picos at, std::uint32_t copy_words) {
  if (!mpu_.on()) return;
  mpu_now_.doing = d;
  mpu_now_.since = at;
  mpu_now_.words = copy_words;
  mpu_now_.word_ps = copy_words ? t_.mpu_cycles_ps(t_.mpu_cycles_per_word_copy) : 0;
  mpu_.change(mpu_now_);
}

void NodeComputer::mpu_activity(std::uint16_t code, std::uint32_t detail) {
  if (!mpu_.on()) return;  // not recorded: nothing reads it
  mpu_now_.code = code;
  mpu_now_.detail = detail;
  const Picos t = now();
  mpu_is(mpu_now_.doing, t, mpu_now_.words_left(t));
}

void NodeComputer::mpu_work(std::uint64_t cycles) { work(MpuDoing::Compute, cycles); }

void NodeComputer::mpu_work_as(Work kind, std::uint64_t cycles) {
  work(kind == Work::Copy ? MpuDoing::Copy : kind == Work::Command ? MpuDoing::Command : MpuDoing::Compute, cycles);
}

void NodeComputer::work(MpuDoing d, std::uint64_t cycles) {
  const Picos t = now();
  mark(Activity::Busy, t);
  if (mpu_.on()) {
    const std::uint64_t per_word = std::max<std::uint64_t>(1, t_.mpu_cycles_per_word_copy);
    mpu_is(d, t, d == MpuDoing::Copy ? static_cast<std::uint32_t>(cycles / per_word) : 0);
  }
  const Picos ps = t_.mpu_cycles_ps(cycles);
  stats_.mpu_busy += ps;
  advance(ps, t);
}

void NodeComputer::send_to_rc(const std::vector<std::uint8_t>& msg) {
  // Copy into the controller's buffer and start it; the controller sends
  // while the MPU goes on (a posted write on the HDLC channel).
  work(MpuDoing::HdlcIo, (msg.size() + 1) / 2 * t_.mpu_cycles_per_word_copy);
  check_alive();
  std::vector<std::uint8_t> data = msg;
  tlm::tlm_generic_payload p;
  p.set_command(tlm::TLM_WRITE_COMMAND);
  p.set_address(0);
  p.set_data_ptr(data.data());
  p.set_data_length(static_cast<unsigned>(data.size()));
  p.set_streaming_width(static_cast<unsigned>(data.size()));
  p.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
  sc_core::sc_time delay = qk_.get_local_time();
  nc2rc_hdlc->b_transport(p, delay);
  if (!p.is_response_ok())
    throw std::runtime_error("NC " + std::to_string(id_) + ": HDLC refused a message: " +
                             p.get_response_string());
  qk_.set(delay);
  ++stats_.messages_sent;
}

std::vector<std::uint8_t> NodeComputer::receive_from_rc() {
  check_alive();
  if (inbox_.empty()) qk_.sync();  // everything due up to our local time has arrived
  if (inbox_.empty()) mark(Activity::WaitRc, now());
  if (inbox_.empty()) mpu_is(MpuDoing::WaitRc, now());
  std::optional<HdlcMailbox::Message> got =
      kill_at_ == ~Picos{0} ? std::optional<HdlcMailbox::Message>(inbox_.take()) : inbox_.take_until(kill_at_);
  if (!got) throw Killed{};
  HdlcMailbox::Message m = std::move(*got);
  catch_up();  // the APU ran while the MPU waited
  ++stats_.messages_received;
  // Receive interrupt, then copy the message out of the controller's buffer.
  work(MpuDoing::HdlcIo, t_.mpu_cycles_per_interrupt + (m.data.size() + 1) / 2 * t_.mpu_cycles_per_word_copy);
  return std::move(m.data);
}

void NodeComputer::b_transport(tlm::tlm_generic_payload& p, sc_core::sc_time& delay) {
  if (p.get_command() != tlm::TLM_WRITE_COMMAND) {
    p.set_response_status(tlm::TLM_COMMAND_ERROR_RESPONSE);
    return;
  }
  inbox_.put({to_picos(sc_core::sc_time_stamp() + delay), 0,
              std::vector<std::uint8_t>(p.get_data_ptr(), p.get_data_ptr() + p.get_data_length())});
  p.set_response_status(tlm::TLM_OK_RESPONSE);
}

void NodeComputer::apu_wait_swap() {
  mark(Activity::Busy, now());
  mpu_is(MpuDoing::WaitSwap, now());
  catch_up();
  if (driver_.data_ready() && engine_->state() != apu::RunState::Running)
    throw std::runtime_error("NC " + std::to_string(id_) +
                             ": waiting for the APU to take a data bank, but the APU is not running");
  // Not past the kill time (the processor stops there), nor past the watchdog's budget.
  const std::uint64_t to_kill =
      kill_at_ == ~Picos{0} ? ~std::uint64_t{0} : kill_at_ > apu_time_ ? (kill_at_ - apu_time_) / cycle_ps_ : 0;
  const std::uint64_t limit = std::min(to_kill, t_.apu_watchdog_cycles);
  engine_->set_time(apu_time_, cycle_ps_);  // the run starts at apu_time_ (waveforms, profiles)
  // Up to the cycle the APU takes the bank (the swap interrupt comes in it),
  // in stretches that end where the NC's steps on the pool do.
  const std::uint64_t n = run_on_pool([this, limit, k = std::uint64_t{0}](ApuJob& job) mutable -> std::optional<std::uint64_t> {
    HostTimer timer(apu_host_ticks_, apu_host_sim_ticks_);
    const auto waiting = [&] { return driver_.data_ready() && engine_->state() == apu::RunState::Running && k < limit; };
    if (waiting()) k += driver_.run_until_data_taken(std::min(limit - k, kPoolStepCycles - (k + 1) % kPoolStepCycles));
    if (!waiting()) return k;
    job.reached(k + 1);
    return std::nullopt;
  });
  stats_.apu_cycles += n;
  apu_time_ += n * cycle_ps_;
  if (driver_.data_ready() && engine_->state() == apu::RunState::Running) {
    if (t_.apu_watchdog_cycles < to_kill) watchdog_expired("took no data bank in " + std::to_string(n) + " cycles");
    const Picos t = now();
    advance(kill_at_ > t ? kill_at_ - t : 0);  // the kill time came first: throws Killed
  }
  check_fault();
  if (driver_.data_ready())
    throw std::runtime_error("NC " + std::to_string(id_) + ": the APU stopped without taking the data bank");
  if (engine_->state() != apu::RunState::Running) apu_stopped(apu_time_);
  const Picos t = now();
  if (apu_time_ > t) advance(apu_time_ - t);
  mpu_work(t_.mpu_cycles_per_interrupt);
}

void NodeComputer::apu_wait_halt() {
  mark(Activity::Busy, now());
  mpu_is(MpuDoing::WaitHalt, now());
  catch_up();
  if (engine_->state() != apu::RunState::Running) return;
  std::string runaway;  // the driver's account of a run the watchdog stops
  engine_->set_time(apu_time_, cycle_ps_);  // the run starts at apu_time_ (waveforms, profiles)
  driver_.begin_run();
  // run_until_done() a stretch at a time: each up to the next cycle whose
  // number is a multiple of kPoolStepCycles, where the NC's steps end.
  const std::uint64_t c0 = engine_->cycle();
  const std::uint64_t n = run_on_pool([this, &runaway, c0, done = std::uint64_t{0}](
                                          ApuJob& job) mutable -> std::optional<std::uint64_t> {
    HostTimer timer(apu_host_ticks_, apu_host_sim_ticks_);
    const std::uint64_t max = t_.apu_watchdog_cycles;
    const auto running = [&] { return engine_->state() == apu::RunState::Running && done < max; };
    if (running()) {
      const std::uint64_t c = engine_->cycle();
      if (c % kPoolStepCycles == 0) job.reached(c - c0 + 1);
      done += driver_.run(std::min(max - done, kPoolStepCycles - c % kPoolStepCycles));
      if (running()) return std::nullopt;
    }
    try {
      return driver_.end_run(done, max);
    } catch (const apu::ApuError& e) {
      if (e.kind() != apu::ApuError::Kind::CycleLimit)
        throw std::runtime_error("NC " + std::to_string(id_) + ": " + e.what());
      runaway = e.what();
      return t_.apu_watchdog_cycles;
    }
  });
  stats_.apu_cycles += n;
  apu_time_ += n * cycle_ps_;
  if (!runaway.empty()) watchdog_expired("no HALT: " + runaway);
  apu_stopped(apu_time_);
  const Picos t = now();
  if (apu_time_ > t) advance(apu_time_ - t);
  apu_time_ = std::max(apu_time_, now());
  mpu_work(t_.mpu_cycles_per_interrupt);
}

void NodeComputer::send_pixels(const PixelRun& run) {
  check_alive();
  pixel_bytes_ = encode_run(run);
  const Picos requested = now();
  mark(Activity::WaitBus, requested);
  mpu_is(MpuDoing::WaitBus, requested);
  pixels_.set_command(tlm::TLM_WRITE_COMMAND);
  pixels_.set_address(0);
  pixels_.set_data_ptr(pixel_bytes_.data());
  pixels_.set_data_length(static_cast<unsigned>(pixel_bytes_.size()));
  pixels_.set_streaming_width(static_cast<unsigned>(pixel_bytes_.size()));
  pixels_.set_byte_enable_ptr(nullptr);
  pixels_.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
  pixel_ext_ = NcIdExtension{};
  pixel_ext_.nc = id_;
  pixels_.set_extension(&pixel_ext_);
  sc_core::sc_time delay = qk_.get_local_time();
  nc2bus_pixels->b_transport(pixels_, delay);  // synchronises: the bus arbitrates in real time
  pixels_.clear_extension(&pixel_ext_);
  qk_.set(delay);
  if (!pixels_.is_response_ok())
    throw std::runtime_error("NC " + std::to_string(id_) + ": image bus refused the run at (" +
                             std::to_string(run.x) + ", " + std::to_string(run.y) + "): " +
                             pixels_.get_response_string());
  // Waiting until the grant, busy while the run is on the bus.
  mark(Activity::Busy, pixel_ext_.granted_known ? pixel_ext_.granted : now());
  mpu_is(MpuDoing::BusOut, pixel_ext_.granted_known ? pixel_ext_.granted : now());
  catch_up();
  ++stats_.runs;
  stats_.pixels += run.pixels.size();
}

void NodeComputer::block_begin(std::uint32_t block) {
  block_ = block;
  mpu_now_.block = block;
  mark(Activity::Busy, now());
}

void NodeComputer::block_end() {
  block_ = 0xFFFFFFFF;
  mpu_now_.block = block_;
  ++stats_.blocks;
  mark(current_, now());
}

void NodeComputer::finished() {
  if (finished_) return;
  catch_up();
  qk_.sync();
  block_ = 0xFFFFFFFF;
  mark(Activity::Idle, now());
  mpu_is(MpuDoing::Done, now());
  stats_.finished_at = now();
  finished_ = true;
}

void NodeComputer::milestone(const std::string& name) { stats_.milestones.emplace_back(name, now()); }
void NodeComputer::phase(const std::string& name) { stats_.phases.emplace_back(now(), name); }

void NodeComputer::die() {
  settle_apu();
  const Picos t = std::max(since_, std::min(now(), kill_at_));
  apu_stopped(std::max(apu_begin_, std::min(apu_time_, t)));
  block_ = 0xFFFFFFFF;
  mark(Activity::Dead, t);
  mpu_is(MpuDoing::Dead, t);
  stats_.killed = true;
  stats_.killed_at = t;
}

// The APU watchdog (docs/reliability.md): the kernel ran the whole budget
// without the swap or HALT the MPU waits for. The NC's processor stops where
// the APU's time has got to, and its HDLC station with it; the RC's link
// supervision then takes the NC as lost, as after --kill-node.
void NodeComputer::watchdog_expired(const std::string& what) {
  stats_.watchdog = true;
  stats_.fault = "APU watchdog (" + std::to_string(t_.apu_watchdog_cycles) + " cycles): " + what;
  kill_at_ = std::min(kill_at_, std::max(apu_time_, now()));
  if (on_stop_) on_stop_(kill_at_);
  advance(kill_at_ - now());  // reaches the stop: throws Killed
  throw Killed{};
}

void NodeComputer::close(Picos frame_end) {
  settle_apu();
  if (!stats_.killed) catch_up();
  apu_stopped(std::min(apu_time_, frame_end));
  mark(current_, frame_end);
  const apu::ApuCounters& counted = engine_->counters();
  stats_.apu_issued = counted.issued;
  stats_.apu_bank_stalls = counted.stalls[static_cast<int>(apu::Stall::Bank)];
  for (int k = 0; k < apu::kStallKinds; ++k) stats_.apu_stalls[k] = counted.stalls[k];
  const double per_tick = seconds_per_tick();  // one rate for both
  stats_.apu_host_seconds = static_cast<double>(apu_host_ticks_) * per_tick;
  stats_.apu_host_simulation_seconds = static_cast<double>(apu_host_sim_ticks_) * per_tick;
  engine_->set_time(std::max(apu_time_, frame_end), cycle_ps_);  // a waveform's idle tail ends with the frame
  for (Picos& p : stats_.time) p = 0;
  for (const Span& s : spans_) stats_.time[static_cast<int>(s.what)] += s.end - s.begin;
}

void NodeComputer::run() {
  const FlagGuard in_thread(in_thread_);
  try {
    firmware_(*this);
    finished();
  } catch (const Killed&) {
    try {
      die();
    } catch (const sc_core::sc_unwind_exception&) {
      throw;
    } catch (const std::exception& e) {  // an APU fault in a catch-up not yet clocked (settle_apu)
      unwind_threads();
      SC_REPORT_ERROR(name(), e.what());
    }
  } catch (const sc_core::sc_unwind_exception&) {
    throw;  // killed at the end of the simulation (unwind_threads): not a failure
  } catch (const std::exception& e) {
    unwind_threads();  // the error ends the simulation: nothing waits on
    SC_REPORT_ERROR(name(), e.what());
  }
}

}  // namespace mc1::nc
