// FP24 golden vectors on the installed package: the C++ model (MC1::fp24) and
// the verilated units (MC1::fp24_rtl) must both give every expected line of
// VEC's EXPECTED ("value flags", hex). Exit 0 all equal, 1 a mismatch, 2 usage.
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

#include <mc1/fp24.hpp>
#include <mc1/fp24_rtl.hpp>

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: fp24_known VEC EXPECTED\n";
    return 2;
  }
  using namespace mc1::fp24;
  std::ifstream vec(argv[1]), expected(argv[2]);
  if (!vec || !expected) {
    std::cerr << "fp24_known: cannot read " << (vec ? argv[2] : argv[1]) << "\n";
    return 2;
  }
  int lines = 0, bad = 0;
  for (std::string line; std::getline(vec, line);) {
    std::istringstream in(line);
    std::string name;
    Bits a = 0, b = 0;
    if (!(in >> name) || name[0] == '#') continue;
    in >> std::hex >> a >> b;
    unsigned value = 0, flags = 0;
    expected >> std::hex >> value >> flags;
    const Op op = *op_from_name(name);
    Result rtl{};
    tb::RtlUnit(info(op).unit).run(op, &a, &b, &rtl, 1);
    for (const Result& r : {execute(op, a, b), rtl})
      if (r.value != value || r.flags != flags) {
        std::printf("%s %06x %06x: got %06x %02x, want %06x %02x\n", name.c_str(), a, b, r.value, r.flags, value,
                    flags);
        ++bad;
      }
    ++lines;
  }
  std::printf("fp24_known: %d vectors, model and RTL, %d mismatches\n", lines, bad);
  return bad || lines == 0 ? 1 : 0;
}
