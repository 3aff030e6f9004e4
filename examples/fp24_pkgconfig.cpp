// Built with `c++ fp24_pkgconfig.cpp $(pkg-config --cflags --libs mc1)`: the
// FP24 model, the assembler and the ISS from mc1.pc alone. Prints 1+2 and the
// cycles of a two-word program; exit 0 when both are as the model says.
#include <cstdio>

#include <mc1/apu_driver.hpp>
#include <mc1/apu_iss.hpp>
#include <mc1/apuasm.hpp>
#include <mc1/fp24.hpp>

int main() {
  const mc1::fp24::Result three = mc1::fp24::add(0x3F0000, 0x400000);  // 1 + 2
  mc1::apu::Iss iss;
  mc1::apu::ApuDriver drv(iss);
  drv.load_program(mc1::apuasm::assemble("lif f1, 3.0\nhalt\n").words);
  drv.hand_over_program();
  drv.start(0);
  const unsigned long long cycles = drv.run_until_done(100);
  std::printf("fp24_pkgconfig: 1+2 = %06x, lif f1 = %06x, %llu cycles\n", three.value, iss.freg(1), cycles);
  return three.value == 0x408000 && iss.freg(1) == 0x408000 ? 0 : 1;
}
