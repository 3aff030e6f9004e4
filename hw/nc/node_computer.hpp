// A node computer (s2): a 16-bit MPU running firmware and an APU with
// dual-bank program and data memories, an HDLC link to the RC and a port on
// the image bus.
//
// Loosely timed with temporal decoupling (tlm_quantumkeeper): MPU work is
// annotated from the timing table, and the NC synchronises with the kernel
// only where it waits for something (a message, the image bus, its APU on
// the pool), never merely at the quantum: nothing simulated depends on
// where it synchronises (the HDLC channel delivers on its own time grid); the APU engine (ISS or verilated RTL,
// chosen at run time) is clocked in bulk: k cycles of APU work annotate
// k x apu_cycle_ps, with no SystemC event per cycle. The MPU and the APU
// share one timeline: whenever the MPU's time advances (work, waiting for
// a message or the bus), the APU is clocked for the same span.
//
// Activity (for statistics and the Gantt chart) partitions the NC's time:
// WaitRc (waiting for a message from the RC: download, the next block),
// Busy (MPU or APU working on a block, pixels on the bus), WaitBus (waiting
// for an image-bus grant), Idle (after Finish), Dead (after a kill).
//
// Fault injection (--kill-node): kill_at(T) stops the NC's processor at
// simulated time T: the MPU firmware and the APU stop where they are (the
// first time the NC's local time reaches T), nothing more is handed to the
// HDLC controller. The MPU runs the link protocol, so the NC's HDLC station
// falls silent at T too (the machine stops it with the NC:
// HdlcChannel::stop_station): no acknowledgement, no answer to a poll, and
// a message still in its controller is not finished; the RC's link
// supervision finds it (docs/hdlc.md). (A kill inside apu_wait_halt() stops
// the NC's time at T, but the APU run in progress is clocked to its HALT:
// its cycles count in apu_cycles.)
#pragma once

#include <atomic>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <systemc>
#include <tlm>
#include <tlm_utils/simple_initiator_socket.h>
#include <tlm_utils/simple_target_socket.h>
#include <tlm_utils/tlm_quantumkeeper.h>
#include <vector>

#include "apu_driver.hpp"
#include "apu_engine.hpp"
#include "apu_pool.hpp"
#include "hdlc_mailbox.hpp"
#include "mpu_activity.hpp"
#include "nc_extension.hpp"
#include "nc_port.hpp"
#include "timing_params.hpp"

namespace mc1::nc {

enum class Activity : std::uint8_t { WaitRc, Busy, WaitBus, Idle, Dead };
constexpr int kActivityKinds = 5;
const char* activity_name(Activity a);

struct Span {
  Picos begin = 0, end = 0;
  Activity what = Activity::WaitRc;
  std::uint32_t block = 0xFFFFFFFF;  // the block being worked on, if any
};

struct ApuSpan {
  Picos begin = 0, end = 0;  // start() to HALT
};

struct NcStats {
  Picos time[kActivityKinds] = {};  // by Activity, after close()
  Picos apu_running = 0;            // APU started and not yet halted
  std::uint64_t apu_cycles = 0;     // cycles clocked while running
  std::uint64_t blocks = 0, pixels = 0, runs = 0;
  std::uint64_t messages_sent = 0, messages_received = 0;
  Picos finished_at = 0;
  bool killed = false;
  Picos killed_at = 0;
  bool watchdog = false;  // stopped by the APU watchdog (killed is set too)
  std::string fault;      // what the watchdog saw
  std::vector<std::pair<std::string, Picos>> milestones;  // in the order reached
  std::vector<std::pair<Picos, std::string>> phases;      // step changes, in time order (phase())
  Picos mpu_busy = 0;               // MPU work annotated (copies, commands, interrupts)
  double apu_host_seconds = 0;      // host time spent clocking the APU engine (set by close())
  double apu_host_simulation_seconds = 0;  // the part of it on the simulation's own thread
  // The engine's counters (apu::ApuCounters, set by close()): words issued,
  // and cycles stalled on `bank` (the APU waiting for the MPU's hand-over).
  std::uint64_t apu_issued = 0, apu_bank_stalls = 0;
  std::uint64_t apu_stalls[apu::kStallKinds] = {};  // stall cycles by apu::Stall
};

class NodeComputer : public sc_core::sc_module, public NcPort {
 public:
  tlm_utils::simple_initiator_socket<NodeComputer> nc2rc_hdlc;
  tlm_utils::simple_target_socket<NodeComputer> hdlc2nc;
  tlm_utils::simple_initiator_socket<NodeComputer> nc2bus_pixels;

  NodeComputer(sc_core::sc_module_name name, const TimingParams& t, unsigned id,
               std::unique_ptr<apu::ApuEngine> engine, Firmware firmware);
  ~NodeComputer() override;

  // Stop the processor at `t` (before sc_start()).
  void kill_at(Picos t) { kill_at_ = t; }
  // Called with the time the processor stops on its own (the APU watchdog),
  // so that the machine can stop the NC's HDLC station with it.
  void on_stop(std::function<void(Picos)> f) { on_stop_ = std::move(f); }
  bool killed() const { return stats_.killed; }
  // The host threads that clock the APU while the MPU waits for it
  // (apu_wait_swap, apu_wait_halt); none (the default): this thread.
  void use_pool(ApuPool* pool) { pool_ = pool; }
  // The least an NC waiting for its APU on the pool moves in simulated time
  // at a step (NodeComputer::run_on_pool; it moves as far as the run is
  // known to last), and the length of a stretch of APU clocking on the
  // pool: a trade between the overlap of the NCs' runs and the number of
  // synchronisations. Not a hardware figure, and no simulated time depends
  // on it. Long (2026-12-05: 4096, from 256): most runs then end within
  // one stretch (an APU batch is some hundreds to thousands of cycles), so
  // a run goes back to the queue, and to the other thread's core and
  // caches, far less often; the 256x256 16-NC ISS frame at 2 threads took
  // about a quarter less host time (docs/platform.md, Rendering benchmark).
  static constexpr std::uint64_t kPoolStepCycles = 4096;
  // The least catch-up (APU cycles owed) an NC hands to the pool's workers
  // while its MPU works on (it then synchronises, so that the kernel runs
  // the other NCs meanwhile): small, so that the workers keep every NC's
  // APU near its MPU's time and the simulation's thread rarely has to clock
  // it itself (the MPU's next hand-over waits for it), but not so small
  // that every few cycles of MPU work post a job (64, from 16). No
  // simulated time depends on it.
  static constexpr std::uint64_t kChaseCycles = 64;

  // After the simulation: the last span runs to `frame_end` (>= finished_at).
  void close(Picos frame_end);  // also reads the ISS's counters
  const std::vector<Span>& spans() const { return spans_; }
  const std::vector<ApuSpan>& apu_spans() const { return apu_spans_; }
  const NcStats& stats() const { return stats_; }
  bool is_finished() const { return finished_; }
  apu::ApuEngine& engine() { return *engine_; }
  // The MPU's side on simulated time (mpu_activity.hpp), recorded from the
  // start if asked before sc_start() (a waveform, the stall profile).
  void record_mpu(bool on) { mpu_.set_on(on); }
  MpuTimeline& mpu_timeline() { return mpu_; }

  // NcPort.
  unsigned id() const override { return id_; }
  const TimingParams& timing() const override { return t_; }
  void mpu_work(std::uint64_t cycles) override;
  void mpu_work_as(Work kind, std::uint64_t cycles) override;
  void mpu_activity(std::uint16_t code, std::uint32_t detail) override;
  void send_to_rc(const std::vector<std::uint8_t>& msg) override;
  std::vector<std::uint8_t> receive_from_rc() override;
  apu::ApuDriver& apu() override { return driver_; }
  void apu_wait_swap() override;
  void apu_wait_halt() override;
  void send_pixels(const PixelRun& run) override;
  void block_begin(std::uint32_t block) override;
  void block_end() override;
  void finished() override;
  void milestone(const std::string& name) override;
  void phase(const std::string& name) override;

 private:
  void run();
  void b_transport(tlm::tlm_generic_payload& p, sc_core::sc_time& delay);
  Picos now() const;
  void advance(Picos ps) { advance(ps, now()); }  // local time + APU catch-up
  void advance(Picos ps, Picos t);     // ... from t = now()
  void catch_up();                     // clock the APU up to now()
  void catch_up_to(Picos t);           // ... up to t (on any thread: no SystemC)
  void settle_apu();                   // the lazy catch-up done: the engine up to date
  void touch_mpu_bank();               // driver_'s bank hook
  bool defer_hand_over();              // driver_'s hand-over hook
  void join_job();                     // the catch-up job's end (and its hand-over)
  void apu_stopped(Picos at);
  void check_fault() const;
  void mark(Activity a, Picos at);     // from `at` on, the NC does `a`
  void work(MpuDoing d, std::uint64_t cycles);  // mpu_work, recorded as `d`
  void mpu_is(MpuDoing d, Picos at, std::uint32_t copy_words = 0);  // the MPU's side (record_mpu)
  void check_alive();                  // throws Killed at or after the kill time
  void die();
  [[noreturn]] void watchdog_expired(const std::string& what);
  std::uint64_t run_on_pool(ApuJob::Stretch stretch);
  bool parallel() const { return pool_ && pool_->threads() > 1; }  // a worker clocks APUs

  TimingParams t_;
  unsigned id_;
  std::unique_ptr<apu::ApuEngine> engine_;
  apu::ApuDriver driver_;
  Firmware firmware_;
  HdlcMailbox inbox_;
  tlm_utils::tlm_quantumkeeper qk_;
  Picos cycle_ps_;
  bool bank_while_running_;  // engine_->mpu_bank_while_running(), asked once

  Picos apu_time_ = 0;      // the APU is clocked up to here
  std::uint64_t apu_host_ticks_ = 0;  // host clock ticks spent clocking the APU (HostTimer)
  std::uint64_t apu_host_sim_ticks_ = 0;  // the part of them on the simulation's thread
  bool apu_open_ = false;   // an ApuSpan is open
  Picos apu_begin_ = 0;

  Activity current_ = Activity::WaitRc;
  Picos since_ = 0;
  std::uint32_t block_ = 0xFFFFFFFF;       // the block being worked on
  std::uint32_t span_block_ = 0xFFFFFFFF;  // the block of the open span
  std::vector<Span> spans_;
  std::vector<ApuSpan> apu_spans_;
  NcStats stats_;
  bool finished_ = false;
  Picos kill_at_ = ~Picos{0};
  std::function<void(Picos)> on_stop_;
  ApuPool* pool_ = nullptr;
  ApuPool inline_{1};
  std::shared_ptr<ApuJob> job_;  // the run on the pool, until the NC has its result
  Picos apu_due_ = 0;            // the APU is to be clocked up to here (advance(): lazily)
  bool apu_due_set_ = false;
  std::atomic<Picos> chase_due_{0};  // apu_due_, for a catch-up job on the pool
  // A data hand-over the catch-up job makes once the APU is clocked up to
  // hand_over_at_ (defer_hand_over): set by the NC, cleared by the job.
  std::atomic<bool> hand_over_due_{false};
  Picos hand_over_at_ = 0;  // written before hand_over_due_ is set
  bool settling_ = false;
  bool in_thread_ = false;  // in run(): the NC's thread may wait

  tlm::tlm_generic_payload pixels_;
  std::vector<std::uint8_t> pixel_bytes_;
  NcIdExtension pixel_ext_;
  MpuTimeline mpu_;
  MpuState mpu_now_;
};

}  // namespace mc1::nc
