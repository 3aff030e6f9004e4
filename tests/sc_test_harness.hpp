// GoogleTest harness for SystemC tests: SystemC reports of severity warning or
// worse become test failures, each test gets a fresh simulation kernel, and
// the SystemC banner is kept off stdout (gtest_discover_tests parses it).
//
// A test file that uses SystemC includes this header once and writes
// MC1_SYSTEMC_GTEST_MAIN() at file scope: libsystemc supplies main() and calls
// sc_main, which runs the tests.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <systemc>

#include "sc_kernel.hpp"

namespace mc1::test {

inline void report_to_gtest(const sc_core::sc_report& r, const sc_core::sc_actions& actions) {
  if (r.get_severity() >= sc_core::SC_WARNING)
    ADD_FAILURE() << "SystemC " << (r.get_severity() == sc_core::SC_WARNING ? "warning" : "error")
                  << " [" << r.get_msg_type() << "] " << r.get_msg() << " at " << r.get_file_name()
                  << ":" << r.get_line_number();
  // Do not let the default handler abort or throw: the failure is recorded.
  sc_core::sc_report_handler::default_handler(
      r, actions & ~(sc_core::SC_THROW | sc_core::SC_ABORT | sc_core::SC_STOP |
                     sc_core::SC_INTERRUPT | sc_core::SC_DISPLAY | sc_core::SC_LOG));
}

// SystemC cannot elaborate twice in one kernel; a test starts a new one (the
// previous kernel is deleted). A test that runs its own modules with
// mc1::sc_run() calls mc1::unwind_threads() before they go, if their threads
// may still be waiting (sc_kernel.hpp).
inline void fresh_kernel() {
  mc1::fresh_kernel();
  sc_core::sc_report_handler::set_handler(report_to_gtest);
}

// After the test: a simulation run by sc_start() itself, not mc1::sc_run(),
// leaves AddressSanitizer on the stack of a SystemC thread (sc_kernel.hpp);
// the test fails, and the thread's own stack is announced again.
class SystemCTest : public ::testing::Test {
 protected:
  void SetUp() override { fresh_kernel(); }
  void TearDown() override {
    if (mc1::sanitizer_on_own_stack())
      ADD_FAILURE() << "ASan was left on a SystemC thread's stack: run simulations with mc1::sc_run(), not sc_start()";
  }
};

}  // namespace mc1::test

#define MC1_SYSTEMC_GTEST_MAIN()                                                     \
  [[maybe_unused]] static const int mc1_no_systemc_banner =                         \
      setenv("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "1", 1);                           \
  int sc_main(int argc, char** argv) {                                               \
    ::testing::InitGoogleTest(&argc, argv);                                          \
    return RUN_ALL_TESTS();                                                          \
  }
