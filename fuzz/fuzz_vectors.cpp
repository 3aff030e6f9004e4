// libFuzzer: the FP24 vector reader (docs/fp24.md "Vector interface").
// Properties: malformed text is refused with VectorError (nothing else
// escapes), and every line it accepts formats back to a line that parses to
// the same vector.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>

#include "fp24_vectors.hpp"

using namespace mc1::fp24::tb;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::istringstream in(text);
  std::vector<Issue> vs;
  try {
    vs = read_vectors(in, "fuzz.vec");
  } catch (const VectorError&) {
    return 0;
  }
  for (const Issue& v : vs) {
    const std::string line = format_vector(v);
    const std::optional<Issue> again = parse_vector(line, "formatted", 1);
    if (!again || format_vector(*again) != line) {
      std::fprintf(stderr, "fuzz_vectors: \"%s\" does not read back\n", line.c_str());
      std::abort();
    }
  }
  return 0;
}
