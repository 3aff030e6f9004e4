// The host threads that clock the APUs of a machine (--threads N). An NC
// waiting for its APU (apu_wait_swap, apu_wait_halt) hands the run to the
// pool as an ApuJob and waits it out in simulated time, while the other NCs
// go on and hand over theirs: the runs of different NCs in one stretch of
// simulated time are clocked at once, one NC's engine by one thread at a
// time. Nothing simulated depends on the threads: the job reports how far
// the run has got, and the NC only ever waits as far as the run is known to
// last (NodeComputer::run_on_pool), so every time is the one-thread time.
//
// A run is clocked a stretch at a time (some thousands of cycles), and the
// runs waiting take turns: the N - 1 workers and the simulation's own
// thread, which clocks stretches whenever it would otherwise wait for a run
// to get far enough (the run it waits for first, if no worker has it). So
// N threads keep N cores busy, and every run moves on at about the pace the
// simulation needs it.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

namespace mc1::nc {

class ApuPool;

// One APU run on the pool.
class ApuJob {
 public:
  // Clocks the run's next stretch: the run's cycle count once it is over,
  // nothing while it goes on. Stretches of one job run one at a time, in
  // order, on any of the pool's threads.
  using Stretch = std::function<std::optional<std::uint64_t>(ApuJob&)>;
  ApuJob(ApuPool& pool, Stretch stretch) : pool_(pool), stretch_(std::move(stretch)) {}

  // In a stretch: the run lasts at least `cycles` cycles (told the
  // simulation when the stretch ends).
  void reached(std::uint64_t cycles) { stretch_reached_ = cycles; }

  // Simulation side. These clock stretches on the calling thread while they
  // wait. Once the run is known to last at least `cycles` cycles or is
  // over: how many cycles it is known to last while it goes on (>= cycles),
  // or 0 if it is over (its length, or its exception, is then result()).
  std::uint64_t known(std::uint64_t cycles);
  // The run's cycle count, or its exception, once it is over.
  std::uint64_t result();
  // Whether the run is over, at once (clocks nothing, waits for nothing).
  bool over();
  // No more stretches: returns once none runs (the job is dropped).
  void cancel();

  // True on a thread while it clocks a stretch (the job's own calls into
  // the driver need no bringing up to date).
  static bool in_job();
  // True on one of a pool's workers (not the simulation's own thread).
  static bool on_worker();

 private:
  friend class ApuPool;
  ApuPool& pool_;
  Stretch stretch_;
  std::uint64_t stretch_reached_ = 0;  // the holding thread's alone
  // Guarded by pool_.m_.
  bool held_ = false;  // a thread clocks a stretch
  bool done_ = false;
  std::atomic<bool> over_{false};  // done_, for over() without the lock
  std::uint64_t reached_ = 0;
  std::uint64_t cycles_ = 0;
  std::exception_ptr error_;
};

class ApuPool {
 public:
  // `threads` host threads clock the APUs: the simulation's own and
  // threads - 1 workers. threads <= 1: no worker, a job is clocked to its
  // end inside post(). 0 is not a count (the caller's default is
  // default_threads()). A thread the host refuses to start: the workers
  // started are joined and std::runtime_error names the thread.
  explicit ApuPool(unsigned threads);
  ~ApuPool();
  ApuPool(const ApuPool&) = delete;
  ApuPool& operator=(const ApuPool&) = delete;

  unsigned threads() const { return threads_; }
  std::shared_ptr<ApuJob> post(ApuJob::Stretch stretch);

  // The host threads a frame takes when not told (--threads): as many as
  // the host has idle cores now, at least 1. A second thread pays only
  // with a core of its own: on a 2-core host with one other busy process
  // two threads took 0.98-1.25x the wall time of one (docs/platform.md
  // "Host threads"). It is threads_for(usable_cpus(), other_runnable()).
  static unsigned default_threads();
  // The CPUs this process may run on (its affinity mask; at least 1).
  static unsigned usable_cpus();
  // The host's other runnable threads now: /proc/loadavg's count of
  // runnable tasks less the reading thread, the mean of 5 reads 1 ms
  // apart (about 5 ms); -1 if it cannot be read. An instant figure, not
  // the load average, which still counts a job that ended a minute ago
  // (this process's own last frame among them).
  static double other_runnable();
  // `cpus` CPUs with `others` of them busy (-1: unknown, all idle):
  // floor(cpus - others + 1/4), within 1..cpus, so that a core busy a
  // quarter of the time or more is not counted as idle.
  static unsigned threads_for(unsigned cpus, double others);

 private:
  friend class ApuJob;
  using Lock = std::unique_lock<std::mutex>;
  // Clocks stretches on this thread until `over` holds for `job`: the
  // job's own when it is free, else any waiting one, else waits.
  template <class Over>
  void help(ApuJob& job, Over over);
  // Clocks `job`'s next stretch, `lock` released meanwhile; the job must
  // be free and out of ready_, and goes back to its end if `requeue`.
  void clock_stretch(Lock& lock, const std::shared_ptr<ApuJob>& job, bool requeue);
  std::shared_ptr<ApuJob> take(ApuJob& job);  // out of ready_, or null
  void push_ready(const std::shared_ptr<ApuJob>& job);
  std::shared_ptr<ApuJob> pop_ready();
  void worker();
  void stop_workers();  // ends and joins every worker

  unsigned threads_;
  std::vector<std::thread> workers_;
  std::mutex m_;
  std::condition_variable work_cv_;      // ready_ got a job, or stopping_
  std::condition_variable progress_cv_;  // a stretch ended
  std::deque<std::shared_ptr<ApuJob>> ready_;  // free jobs not over, in turn
  bool stopping_ = false;
  int sleepers_ = 0;  // workers waiting on work_cv_
  // Read without m_ by spinning threads: ready_'s size, stretches ended.
  std::atomic<std::size_t> ready_n_{0};
  std::atomic<std::uint64_t> ended_{0};
};

}  // namespace mc1::nc
