// libFuzzer: the APU program-image reader and the disassembler. A bad image
// is refused with std::runtime_error; every word of a good one disassembles,
// and the image written back from its words is byte-identical (round trip).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "apu_image.hpp"
#include "disasm.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  std::vector<mc1::apu::Encoded> words;
  try {
    words = mc1::apu::parse_image(bytes, "fuzz.bin");
  } catch (const std::runtime_error&) {
    return 0;
  }
  for (const mc1::apu::Encoded& w : words) {
    (void)mc1::apu::disassemble(w);
    (void)mc1::apu::encoding_hex(w);
  }
  if (mc1::apu::image_bytes(words) != bytes) {
    std::fprintf(stderr, "fuzz_image: an accepted image does not write back byte for byte\n");
    std::abort();
  }
  return 0;
}
