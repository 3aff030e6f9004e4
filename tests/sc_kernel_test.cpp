// The end of a simulation (hw/platform/sc_kernel.hpp): threads still waiting
// are unwound, their frames' objects destroyed, no simulated time passes.
#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "sc_kernel.hpp"
#include "sc_test_harness.hpp"

using namespace sc_core;

namespace {

// Counts its destructions: an object in a thread's frame.
struct Guard {
  int* destroyed;
  explicit Guard(int* d) : destroyed(d) {}
  ~Guard() { ++*destroyed; }
};

SC_MODULE(Waiters) {
  sc_event never;
  int destroyed = 0;      // Guards gone
  int caught = 0;         // exceptions the catching thread took as its own
  bool after_unwind = false;
  sc_time unwound_at;
  bool unwind_from_a_thread = false;

  SC_CTOR(Waiters) {
    SC_THREAD(forever);
    SC_THREAD(catching);
    SC_THREAD(sleeper);
    SC_THREAD(ender);
  }

  // Owns heap memory in its frame and waits for an event that never comes.
  void forever() {
    Guard g(&destroyed);
    std::vector<std::string> owned(100, std::string(64, 'x'));
    wait(never);
  }
  // The pattern of the RC's and the NCs' threads: a catch of std::exception
  // around waits lets sc_unwind_exception through.
  void catching() {
    Guard g(&destroyed);
    try {
      auto owned = std::make_unique<std::vector<int>>(1000);
      wait(never);
    } catch (const sc_unwind_exception&) {
      throw;
    } catch (const std::exception&) {
      ++caught;
    }
  }
  // Waits for a time after the end: its timeout is cancelled.
  void sleeper() {
    Guard g(&destroyed);
    wait(1, SC_SEC);
  }
  // Ends the simulation from a process (as before an SC_REPORT_ERROR).
  void ender() {
    wait(10, SC_NS);
    if (!unwind_from_a_thread) return;
    mc1::unwind_threads();
    after_unwind = true;  // the caller itself runs on
    unwound_at = sc_time_stamp();
  }
};

class ScKernel : public mc1::test::SystemCTest {};

TEST_F(ScKernel, ThreadsWaitingAfterSimulationAreUnwoundAtTheSameTime) {
  Waiters w("w");
  mc1::sc_run(100, SC_NS);
  EXPECT_EQ(w.destroyed, 0);
  const sc_time end = sc_time_stamp();
  mc1::unwind_threads();
  EXPECT_EQ(w.destroyed, 3);
  EXPECT_EQ(w.caught, 0);
  EXPECT_EQ(sc_time_stamp(), end);
  EXPECT_FALSE(sc_pending_activity());
  mc1::unwind_threads();  // nothing left: nothing happens
  EXPECT_EQ(w.destroyed, 3);
}

TEST_F(ScKernel, UnwindsAllButTheCallingThread) {
  Waiters w("w");
  w.unwind_from_a_thread = true;
  mc1::sc_run(100, SC_NS);
  EXPECT_EQ(w.destroyed, 3);
  EXPECT_EQ(w.caught, 0);
  EXPECT_TRUE(w.after_unwind);
  EXPECT_EQ(w.unwound_at, sc_time(10, SC_NS));
}

TEST_F(ScKernel, UnderARootOnly) {
  Waiters a("a");
  Waiters b("b");
  mc1::sc_run(100, SC_NS);
  mc1::unwind_threads(&b);
  EXPECT_EQ(a.destroyed, 0);
  EXPECT_EQ(b.destroyed, 3);
  mc1::unwind_threads();
  EXPECT_EQ(a.destroyed, 3);
}

TEST_F(ScKernel, NothingBeforeTheSimulation) {
  Waiters w("w");
  mc1::unwind_threads();  // elaboration: no process has run
  mc1::sc_run(100, SC_NS);
  EXPECT_EQ(w.destroyed, 0);
  mc1::unwind_threads();
  EXPECT_EQ(w.destroyed, 3);
}

SC_MODULE(Returner) {
  bool done = false;
  SC_CTOR(Returner) { SC_THREAD(run); }
  void run() {
    wait(10, SC_NS);
    done = true;
  }
};

// SystemC switches away from a thread that returns without telling ASan:
// after a plain sc_start() ASan takes the caller for still on that thread's
// stack, which goes with the module (at exit LeakSanitizer's scan of it
// faulted: ApuTlmTest, whose MPU thread returns). sc_run() announces the
// caller's own stack again. Without ASan there is nothing to announce.
TEST_F(ScKernel, AfterAThreadReturnedTheCallerIsOnItsOwnStack) {
#ifndef MC1_ASAN
  GTEST_SKIP() << "only under AddressSanitizer";
#endif
  {
    Returner r("plain");
    sc_start(100, SC_NS);
    ASSERT_TRUE(r.done);
  }
  EXPECT_TRUE(mc1::sanitizer_on_own_stack()) << "SystemC announced its switch away from a thread that returned";
  mc1::test::fresh_kernel();
  {
    Returner r("run");
    mc1::sc_run(100, SC_NS);
    ASSERT_TRUE(r.done);
  }
  EXPECT_FALSE(mc1::sanitizer_on_own_stack());
}

TEST(ScKernelFresh, ANewKernelEachTimeTheOldDeleted) {
  mc1::test::fresh_kernel();
  sc_simcontext* first = sc_get_curr_simcontext();
  {
    Waiters w("w");
    mc1::sc_run(100, SC_NS);
    mc1::unwind_threads();
  }
  mc1::test::fresh_kernel();
  EXPECT_NE(sc_get_curr_simcontext(), first);
  EXPECT_EQ(sc_time_stamp(), SC_ZERO_TIME);
  Waiters w("w");  // the same name elaborates again
  mc1::sc_run(100, SC_NS);
  EXPECT_EQ(sc_time_stamp(), sc_time(100, SC_NS));
  mc1::unwind_threads();
  EXPECT_EQ(w.destroyed, 3);
}

}  // namespace

MC1_SYSTEMC_GTEST_MAIN()
