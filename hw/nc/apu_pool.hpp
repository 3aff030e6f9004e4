// The host threads that clock the APUs of a machine (--threads N). An NC
// waiting for its APU (apu_wait_swap, apu_wait_halt) hands the run to the
// pool as an ApuJob and waits it out in simulated time, while the other NCs
// go on and hand over theirs: the runs of different NCs in one stretch of
// simulated time are clocked at once, one NC's engine by one thread at a
// time. Nothing simulated depends on the threads: the job reports how far
// the run has got, and the NC only ever waits as far as the run is known to
// last (NodeComputer::run_on_pool), so every time is the one-thread time.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace mc1::nc {

// One APU run on the pool. The work returns the run's cycle count and says
// on the way how long the run lasts at least (reached()).
class ApuJob {
 public:
  using Work = std::function<std::uint64_t(ApuJob&)>;
  explicit ApuJob(Work work) : work_(std::move(work)) {}

  // Worker side: the run lasts at least `cycles` cycles.
  void reached(std::uint64_t cycles);

  // Simulation side. Blocks until it is known whether the run lasts at
  // least `cycles` cycles; false also when the work threw.
  bool lasts(std::uint64_t cycles);
  // Blocks until the work is done: its cycle count, or its exception.
  std::uint64_t result();
  void wait_done();

  void execute();  // the pool's
  // True on a thread while it executes a job (the job's own calls into the
  // driver need no bringing up to date).
  static bool in_job();

 private:
  Work work_;
  std::atomic<std::uint64_t> reached_{0};
  std::atomic<std::uint64_t> wanted_{~std::uint64_t{0}};
  std::mutex m_;
  std::condition_variable cv_;
  bool done_ = false;
  std::uint64_t cycles_ = 0;
  std::exception_ptr error_;
};

class ApuPool {
 public:
  // threads <= 1: no worker, a job runs inside post(); 0 is not a count
  // (the machine's cores are the caller's default: default_threads()).
  explicit ApuPool(unsigned threads);
  ~ApuPool();
  ApuPool(const ApuPool&) = delete;
  ApuPool& operator=(const ApuPool&) = delete;

  unsigned threads() const { return threads_; }
  std::shared_ptr<ApuJob> post(ApuJob::Work work);

  // The host's cores (at least 1).
  static unsigned default_threads();

 private:
  void worker();

  unsigned threads_;
  std::vector<std::thread> workers_;
  std::mutex m_;
  std::condition_variable cv_;
  std::deque<std::shared_ptr<ApuJob>> queue_;
  bool stopping_ = false;
};

}  // namespace mc1::nc
