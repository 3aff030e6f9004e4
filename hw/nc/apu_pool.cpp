#include "apu_pool.hpp"

namespace mc1::nc {
namespace {
thread_local bool t_in_job = false;
}  // namespace

bool ApuJob::in_job() { return t_in_job; }

void ApuJob::reached(std::uint64_t cycles) {
  reached_.store(cycles);
  if (cycles >= wanted_.load()) {
    std::lock_guard<std::mutex> lock(m_);
    cv_.notify_all();
  }
}

bool ApuJob::lasts(std::uint64_t cycles) {
  if (reached_.load() >= cycles) return true;
  wanted_.store(cycles);
  std::unique_lock<std::mutex> lock(m_);
  cv_.wait(lock, [&] { return done_ || reached_.load() >= cycles; });
  if (reached_.load() >= cycles) return true;
  return !error_ && cycles_ >= cycles;
}

void ApuJob::wait_done() {
  std::unique_lock<std::mutex> lock(m_);
  cv_.wait(lock, [&] { return done_; });
}

std::uint64_t ApuJob::result() {
  wait_done();
  if (error_) std::rethrow_exception(error_);
  return cycles_;
}

void ApuJob::execute() {
  std::uint64_t n = 0;
  std::exception_ptr e;
  const bool outer = t_in_job;
  t_in_job = true;
  try {
    n = work_(*this);
  } catch (...) {
    e = std::current_exception();
  }
  t_in_job = outer;
  std::lock_guard<std::mutex> lock(m_);
  cycles_ = n;
  error_ = e;
  done_ = true;
  cv_.notify_all();
}

ApuPool::ApuPool(unsigned threads) : threads_(threads < 1 ? 1 : threads) {
  if (threads_ > 1)
    for (unsigned i = 0; i < threads_; ++i) workers_.emplace_back([this] { worker(); });
}

ApuPool::~ApuPool() {
  {
    std::lock_guard<std::mutex> lock(m_);
    stopping_ = true;
  }
  cv_.notify_all();
  for (std::thread& t : workers_) t.join();
}

unsigned ApuPool::default_threads() {
  const unsigned n = std::thread::hardware_concurrency();
  return n ? n : 1;
}

std::shared_ptr<ApuJob> ApuPool::post(ApuJob::Work work) {
  auto job = std::make_shared<ApuJob>(std::move(work));
  if (workers_.empty()) {
    job->execute();
    return job;
  }
  {
    std::lock_guard<std::mutex> lock(m_);
    queue_.push_back(job);
  }
  cv_.notify_one();
  return job;
}

void ApuPool::worker() {
  for (;;) {
    std::shared_ptr<ApuJob> job;
    {
      std::unique_lock<std::mutex> lock(m_);
      cv_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
      if (queue_.empty()) return;  // stopping, nothing left
      job = std::move(queue_.front());
      queue_.pop_front();
    }
    job->execute();
  }
}

}  // namespace mc1::nc
