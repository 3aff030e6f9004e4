// The end of a simulation and of a SystemC kernel (docs/reliability.md,
// "Sanitizers").
//
// SystemC 2.3.4 leaves every SC_THREAD that has not returned suspended in
// its wait() when sc_start() returns, and deleting the kernel unmaps the
// thread's coroutine stack without unwinding it: what the thread's frames
// own (the firmware's vectors and strings, the HDLC pump's queues) is never
// freed, and LeakSanitizer reports it (docs/reliability.md). unwind_threads()
// kills those threads (sc_process_handle::kill: the thread's wait() throws
// sc_core::sc_unwind_exception and its frames unwind), at the current
// simulated time: no process runs on, no time passes.
//
// A thread that catches std::exception or `...` around a wait() must rethrow
// sc_core::sc_unwind_exception first (it is a std::exception):
//   catch (const sc_core::sc_unwind_exception&) { throw; }
#pragma once

#include <systemc>
#include <cstddef>
#include <utility>
#include <vector>

#include "sysc/kernel/sc_dynamic_processes.h"

#if defined(__SANITIZE_ADDRESS__)
#define MC1_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define MC1_ASAN 1
#endif
#endif
#ifdef MC1_ASAN
#include <pthread.h>
#include <sanitizer/common_interface_defs.h>
#endif

namespace mc1 {

// Under AddressSanitizer: tells it that this thread is back on its own
// stack. SystemC 2.3.4 announces its coroutine switches to ASan
// (__sanitizer_start_switch_fiber) but gives the main coroutine a stack of
// size 0, and a thread that ends (returns, or is killed) switches without
// telling: after sc_start() ASan takes the main stack for an empty or a
// finished thread's one, ignores every later throw's request to clean the
// stack ("ASan is ignoring requested __asan_handle_no_return") and then
// reports stack-use-after-scope in code that reuses the frames a throw left
// (first seen in `mc1 render --stats /dev/full`). Once the finished
// thread's stack is unmapped (its module destroyed), LeakSanitizer's scan of
// this thread's "stack" at exit faults ("Tracer caught signal 11 ...
// LeakSanitizer has encountered a fatal error", ApuTlmTest). Returns whether
// ASan had taken another stack for this thread's (false without ASan).
inline bool sanitizer_on_own_stack() {
#ifdef MC1_ASAN
  pthread_attr_t a;
  if (pthread_getattr_np(pthread_self(), &a) != 0) return false;
  void* base = nullptr;
  std::size_t size = 0;
  const int got = pthread_attr_getstack(&a, &base, &size);
  pthread_attr_destroy(&a);
  if (got != 0) return false;
  void* fake = nullptr;
  const void* was = nullptr;
  std::size_t was_size = 0;
  __sanitizer_start_switch_fiber(&fake, base, size);
  __sanitizer_finish_switch_fiber(fake, &was, &was_size);
  const char* here = reinterpret_cast<const char*>(&a);
  const char* from = static_cast<const char*>(was);
  return !(from <= here && here < from + was_size);
#else
  return false;
#endif
}

// sc_start(), and then sanitizer_on_own_stack() (also when it throws). Every
// simulation of ours runs through it, never sc_start() itself (the tests'
// harness fails a test that leaves ASan on a coroutine's stack).
template <typename... Args>
void sc_run(Args&&... args) {
  try {
    sc_core::sc_start(std::forward<Args>(args)...);
  } catch (...) {
    sanitizer_on_own_stack();
    throw;
  }
  sanitizer_on_own_stack();
}

namespace detail {

inline void live_threads(const std::vector<sc_core::sc_object*>& objects, const sc_core::sc_process_handle& self,
                         std::vector<sc_core::sc_process_handle>& out) {
  for (sc_core::sc_object* o : objects) {
    const sc_core::sc_process_handle h(o);
    if (h.valid() && h != self && !h.terminated() &&
        (h.proc_kind() == sc_core::SC_THREAD_PROC_ || h.proc_kind() == sc_core::SC_CTHREAD_PROC_))
      out.push_back(h);
    live_threads(o->get_child_objects(), self, out);
  }
}

inline void kill_all(const std::vector<sc_core::sc_process_handle>& threads) {
  for (sc_core::sc_process_handle h : threads)
    if (!h.terminated()) h.kill();
}

}  // namespace detail

// Unwinds every thread process of the current kernel that has not ended
// (under `root`, if given; never the caller, when called from a process).
// Call it while the modules are alive:
// - after sc_start() returned (paused): a method spawned for it kills the
//   threads in one zero-time delta cycle (SystemC can kill a thread only
//   from a process);
// - from a process that is about to end the simulation with an error
//   (SC_REPORT_ERROR throws out of sc_start(), after which the kernel runs
//   no process any more).
// Does nothing before the simulation has started, after sc_stop(), or once
// an error has ended it.
inline void unwind_threads(const sc_core::sc_object* root = nullptr) {
  sc_core::sc_simcontext* k = sc_core::sc_get_curr_simcontext();
  if (!sc_core::sc_is_running() || k->get_error()) return;
  const sc_core::sc_status s = sc_core::sc_get_status();
  const sc_core::sc_process_handle self =
      s == sc_core::SC_RUNNING ? sc_core::sc_get_current_process_handle() : sc_core::sc_process_handle();
  if (s == sc_core::SC_RUNNING && !self.valid()) return;  // not in a process: an error is on its way out
  if (s != sc_core::SC_RUNNING && s != sc_core::SC_PAUSED) return;
  std::vector<sc_core::sc_process_handle> threads;
  detail::live_threads(root ? root->get_child_objects() : sc_core::sc_get_top_level_objects(), self, threads);
  if (threads.empty()) return;
  if (s == sc_core::SC_RUNNING) {
    detail::kill_all(threads);
    return;
  }
  sc_core::sc_spawn_options o;
  o.spawn_method();
  // The method runs once, within this sc_start() (no sensitivity), and is
  // then ended itself (a method never ends on its own, and a spawned one
  // belongs to no process table: it would be leaked with the kernel). It
  // holds no handle afterwards: the killed threads go with `threads`.
  sc_core::sc_process_handle reaper = sc_core::sc_spawn(
      [&threads] { detail::kill_all(threads); }, sc_core::sc_gen_unique_name("mc1_unwind"), &o);
  sc_run(sc_core::SC_ZERO_TIME);
  reaper.kill();
  // Drops the killed threads' cancelled timeouts from the event queue (the
  // kernel would otherwise keep them until its next time step).
  (void)sc_core::sc_pending_activity_at_future_time();
}

// SystemC elaborates once per kernel: a fresh one for the next
// elaboration. The previous kernel is deleted, with all it still holds (its
// processes, their stacks, its event queue); its modules must be destroyed
// already, its threads unwound (unwind_threads) while they were alive.
// Except the kernel libsystemc made when it was loaded: the library's own
// static objects (sc_process_handle::non_event) belong to it and reach it
// when they are destroyed at exit, so it is kept (reachable, not leaked).
inline void fresh_kernel() {
  static sc_core::sc_simcontext* const library_kernel = sc_core::sc_get_curr_simcontext();
  sc_core::sc_simcontext* old = sc_core::sc_curr_simcontext;
  // A destroyed event's pending timed notification stays in the queue,
  // cancelled, until the kernel looks for its next time: free them now.
  if (old) (void)sc_core::sc_pending_activity_at_future_time(old);
  sc_core::sc_curr_simcontext = new sc_core::sc_simcontext();
  sc_core::sc_default_global_context = sc_core::sc_curr_simcontext;
  if (old != library_kernel) delete old;
}

}  // namespace mc1
