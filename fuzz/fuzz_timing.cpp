// libFuzzer: the timing-parameter reader (docs/timing.md). Bad text is
// refused with ParamError and nothing else; a table it accepts prints
// (to_text) as a file that reads back to the same table.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "timing_params.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  mc1::TimingParams p;
  try {
    mc1::load_params_text(p, std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.params");
  } catch (const mc1::ParamError&) {
    return 0;
  }
  const std::string text = p.to_text();
  mc1::TimingParams q;
  mc1::load_params_text(q, text, "printed");
  if (q.to_text() != text) {
    std::fprintf(stderr, "fuzz_timing: an accepted table does not read back from its own print\n");
    std::abort();
  }
  return 0;
}
