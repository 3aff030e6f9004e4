// main() of every test program without SystemC processes of its own:
// libsystemc defines main() and calls sc_main(), and every test links
// libsystemc (through the project libraries), so every test takes SystemC's
// main and runs GoogleTest from sc_main. (Linking gtest_main's main() first
// instead works with a plain link but not under -fsanitize, where the
// linker then finds libsystemc's reference to sc_main unresolved.)
#include "sc_test_harness.hpp"

MC1_SYSTEMC_GTEST_MAIN()
