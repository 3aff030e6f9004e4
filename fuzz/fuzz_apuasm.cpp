// libFuzzer: the APU assembler (docs/apu-asm.md) on source text. Bad source
// is refused with AsmError; a program it accepts must also list and
// disassemble. A crash, a hang or unbounded memory is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include "apuasm.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  // As if the text were a kernel beside the real ones: .include "r_layout.inc"
  // and the other shared files resolve, as they do for the seeds.
  try {
    const mc1::apuasm::Program p = mc1::apuasm::assemble(text, MC1_FUZZ_KERNEL_DIR "/fuzz.apu");
    (void)mc1::apuasm::listing_text(p);
    (void)mc1::apuasm::disassembly_text(p.words);
  } catch (const mc1::apuasm::AsmError&) {
  }
  return 0;
}
