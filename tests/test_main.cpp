// main() of the test programs whose libraries bring in libsystemc but that
// have no SystemC processes of their own (tests/CMakeLists.txt chooses):
// libsystemc defines main() and calls sc_main(), so such a test takes
// SystemC's main and runs GoogleTest from sc_main. (Linking gtest_main's
// main() first instead works with a plain link but not under -fsanitize,
// where the linker then finds libsystemc's reference to sc_main unresolved.)
// A test that links no SystemC takes gtest_main.
#include "sc_test_harness.hpp"

MC1_SYSTEMC_GTEST_MAIN()
