#include "apu_pool.hpp"

#include <sched.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>

namespace mc1::nc {
namespace {
thread_local bool t_in_job = false;
thread_local bool t_on_worker = false;

// A stretch takes some microseconds: a thread out of work spins about as
// long before it sleeps (a sleep and a wake-up cost more than that).
constexpr int kSpins = 4000;

// The pool's lock is held for a few queue operations at a time: a thread
// that finds it taken spins about a microsecond before it blocks (a futex
// sleep and wake-up cost more than the wait).
constexpr int kLockSpins = 100;

void cpu_relax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#else
  std::this_thread::yield();
#endif
}

// Spins until done() or about kSpins pauses have passed; true if done().
// Every kYieldEvery pauses it gives its core away: when the thread it waits
// for shares this core (a loaded host puts both on one), that one runs now
// instead of after this one's time slice.
constexpr int kYieldEvery = 128;

template <class Done>
bool spin_until(Done done) {
  for (int i = 1; i <= kSpins; ++i) {
    if (done()) return true;
    cpu_relax();
    if (i % kYieldEvery == 0) std::this_thread::yield();
  }
  return done();
}

void acquire(std::unique_lock<std::mutex>& lock) {
  for (int i = 0; i < kLockSpins; ++i) {
    if (lock.try_lock()) return;
    cpu_relax();
  }
  lock.lock();
}
}  // namespace

bool ApuJob::in_job() { return t_in_job; }
bool ApuJob::on_worker() { return t_on_worker; }

std::uint64_t ApuJob::known(std::uint64_t cycles) {
  std::uint64_t n = 0;  // decided under the pool's lock: a worker may publish reached_ after help()
  pool_.help(*this, [&] {
    n = done_ ? 0 : reached_;
    return done_ || reached_ >= cycles;
  });
  return n;
}

std::uint64_t ApuJob::result() {
  pool_.help(*this, [&] { return done_; });
  if (error_) std::rethrow_exception(error_);
  return cycles_;
}

bool ApuJob::over() { return over_.load(std::memory_order_acquire); }

void ApuJob::cancel() {
  ApuPool::Lock lock(pool_.m_);
  pool_.take(*this);
  done_ = true;
  over_.store(true, std::memory_order_release);
  pool_.progress_cv_.wait(lock, [&] { return !held_; });
}

// A thread the host will not start (a process or cgroup limit) ends the
// pool's construction cleanly: the workers already started are stopped and
// joined (a joinable std::thread destroyed would end the program), and the
// error says which thread failed.
ApuPool::ApuPool(unsigned threads) : threads_(threads < 1 ? 1 : threads) {
  try {
    for (unsigned i = 1; i < threads_; ++i) workers_.emplace_back([this] {
      t_on_worker = true;
      worker();
    });
  } catch (const std::system_error& e) {
    const std::size_t started = workers_.size();
    stop_workers();
    throw std::runtime_error("cannot start host thread " + std::to_string(started + 2) + " of " +
                             std::to_string(threads_) + " (--threads): " + e.what());
  }
}

ApuPool::~ApuPool() { stop_workers(); }

void ApuPool::stop_workers() {
  {
    Lock lock(m_);
    stopping_ = true;
    ready_n_.store(1);  // no more spinning
  }
  work_cv_.notify_all();
  for (std::thread& t : workers_) t.join();
  workers_.clear();
}

unsigned ApuPool::usable_cpus() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) == 0 && CPU_COUNT(&set) > 0) return static_cast<unsigned>(CPU_COUNT(&set));
  const unsigned n = std::thread::hardware_concurrency();
  return n ? n : 1;
}

double ApuPool::other_runnable() {
  constexpr int kSamples = 5;
  double sum = 0;
  int got = 0;
  for (int i = 0; i < kSamples; ++i) {
    if (i) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    std::ifstream in("/proc/loadavg");
    double l1, l5, l15;
    unsigned runnable = 0, tasks = 0;
    char slash = 0;
    if (in >> l1 >> l5 >> l15 >> runnable >> slash >> tasks && slash == '/' && runnable >= 1) {
      sum += runnable - 1;  // this thread, reading, is one of them
      ++got;
    }
  }
  return got ? sum / got : -1;
}

unsigned ApuPool::threads_for(unsigned cpus, double others) {
  if (cpus <= 1) return 1;
  if (others < 0) return cpus;  // no load figure: every core
  const double idle = static_cast<double>(cpus) - others;
  return static_cast<unsigned>(std::clamp(std::floor(idle + 0.25), 1.0, static_cast<double>(cpus)));
}

unsigned ApuPool::default_threads() {
  const unsigned cpus = usable_cpus();
  return cpus <= 1 ? 1 : threads_for(cpus, other_runnable());
}

std::shared_ptr<ApuJob> ApuPool::post(ApuJob::Stretch stretch) {
  auto job = std::make_shared<ApuJob>(*this, std::move(stretch));
  Lock lock(m_, std::defer_lock);
  acquire(lock);
  if (workers_.empty()) {
    while (!job->done_) clock_stretch(lock, job, false);
    return job;
  }
  push_ready(job);
  return job;
}

void ApuPool::push_ready(const std::shared_ptr<ApuJob>& job) {
  ready_.push_back(job);
  ready_n_.store(ready_.size(), std::memory_order_release);
  if (sleepers_) work_cv_.notify_one();
}

std::shared_ptr<ApuJob> ApuPool::pop_ready() {
  std::shared_ptr<ApuJob> job = std::move(ready_.front());
  ready_.pop_front();
  ready_n_.store(ready_.size(), std::memory_order_relaxed);
  return job;
}

std::shared_ptr<ApuJob> ApuPool::take(ApuJob& job) {
  const auto it = std::find_if(ready_.begin(), ready_.end(), [&](const auto& j) { return j.get() == &job; });
  if (it == ready_.end()) return nullptr;
  std::shared_ptr<ApuJob> held = std::move(*it);
  ready_.erase(it);
  ready_n_.store(ready_.size(), std::memory_order_relaxed);
  return held;
}

template <class Over>
void ApuPool::help(ApuJob& job, Over over) {
  Lock lock(m_, std::defer_lock);
  acquire(lock);
  while (!over()) {
    std::shared_ptr<ApuJob> next = take(job);
    if (!next && !ready_.empty()) next = pop_ready();
    if (next) {
      clock_stretch(lock, next, true);
      continue;
    }
    // A worker holds the job: its stretch ends soon.
    const std::uint64_t ended = ended_.load(std::memory_order_relaxed);
    lock.unlock();
    spin_until([&] { return ended_.load(std::memory_order_acquire) != ended; });
    acquire(lock);
    if (ended_.load(std::memory_order_relaxed) == ended) progress_cv_.wait(lock);
  }
}

void ApuPool::clock_stretch(Lock& lock, const std::shared_ptr<ApuJob>& job, bool requeue) {
  job->held_ = true;
  lock.unlock();
  std::optional<std::uint64_t> cycles;
  std::exception_ptr error;
  const bool outer = t_in_job;
  t_in_job = true;
  try {
    cycles = job->stretch_(*job);
  } catch (...) {
    error = std::current_exception();
  }
  t_in_job = outer;
  acquire(lock);
  job->held_ = false;
  ended_.fetch_add(1, std::memory_order_release);
  job->reached_ = std::max(job->reached_, job->stretch_reached_);
  if (cycles || error) {
    job->cycles_ = cycles.value_or(0);
    job->error_ = error;
    job->done_ = true;
    job->over_.store(true, std::memory_order_release);
  } else if (requeue && !job->done_) {  // not cancelled meanwhile: its next turn
    push_ready(job);
  }
  progress_cv_.notify_all();
}

void ApuPool::worker() {
  Lock lock(m_);
  for (;;) {
    if (ready_.empty() && !stopping_) {
      lock.unlock();
      spin_until([&] { return ready_n_.load(std::memory_order_acquire) != 0; });
      acquire(lock);
      ++sleepers_;
      work_cv_.wait(lock, [&] { return stopping_ || !ready_.empty(); });
      --sleepers_;
    }
    if (stopping_) return;
    clock_stretch(lock, pop_ready(), true);
  }
}

}  // namespace mc1::nc
