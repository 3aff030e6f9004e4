// apu-run: runs one APU program on the ISS or the RTL core through the MPU
// driver, like firmware would, and prints the outcome, the registers and
// (--profile) a cycle profile (docs/apu-tools.md).
#include <cstdlib>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "apu_driver.hpp"
#include "apu_lockstep.hpp"
#include "apu_profile.hpp"
#include "apu_tools.hpp"

namespace {

using namespace mc1::apu;

constexpr const char* kUsage =
    "usage: apu-run PROGRAM.bin|PROGRAM.apu [--engine iss|rtl] [--data FILE]... [--trace OUT.fst]\n"
    "               [--profile] [--top N] [--read ADDR:COUNT]... [--max-cycles N] [--start PC]\n"
    "Loads the program (and data) into the MPU's banks, hands them over, starts the APU and waits\n"
    "for HALT. Several --data files form a stream: the next is handed over each time the APU\n"
    "has taken the last (SWAPD). Prints cycles and the registers that are not zero; --read prints data words the\n"
    "MPU sees after the run (the bank the APU left with its last SWAPD); --profile prints unit\n"
    "utilization, stalls by reason and the top N stalling words. --trace is for the RTL engine.\n"
    "Exit 0: halted; 1: fault or cycle limit; 2: usage or input error.\n";

[[noreturn]] void usage_error(const std::string& msg) {
  std::cerr << "apu-run: " << msg << "\n" << kUsage;
  std::exit(2);
}

std::uint64_t number(const std::string& opt, const std::string& text) {
  char* end = nullptr;
  const unsigned long long v = std::strtoull(text.c_str(), &end, 0);
  if (text.empty() || *end) usage_error(opt + " wants a number, not '" + text + "'");
  return v;
}

struct Options {
  std::string program, trace, engine = "iss";
  std::vector<std::string> data;
  bool profile = false;
  int top = 10;
  std::uint64_t max_cycles = 100'000'000;
  std::uint16_t start = 0;
  std::vector<std::pair<std::uint16_t, std::uint16_t>> reads;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage_error(a + " wants a value");
      return argv[++i];
    };
    if (a == "--help" || a == "-h") {
      std::cout << kUsage;
      std::exit(0);
    } else if (a == "--engine") {
      o.engine = value();
    } else if (a == "--data") {
      o.data.push_back(value());
    } else if (a == "--trace") {
      o.trace = value();
    } else if (a == "--profile") {
      o.profile = true;
    } else if (a == "--top") {
      o.top = static_cast<int>(number(a, value()));
    } else if (a == "--max-cycles") {
      o.max_cycles = number(a, value());
    } else if (a == "--start") {
      o.start = static_cast<std::uint16_t>(number(a, value()));
    } else if (a == "--read") {
      const std::string v = value();
      const auto colon = v.find(':');
      if (colon == std::string::npos) usage_error("--read wants ADDR:COUNT, not '" + v + "'");
      const auto addr = number(a, v.substr(0, colon)), n = number(a, v.substr(colon + 1));
      if (addr + n > static_cast<std::uint64_t>(kDataWords)) usage_error("--read " + v + " goes past word 4095");
      o.reads.emplace_back(static_cast<std::uint16_t>(addr), static_cast<std::uint16_t>(n));
    } else if (!a.empty() && a[0] == '-') {
      usage_error("unknown option " + a);
    } else if (o.program.empty()) {
      o.program = a;
    } else {
      usage_error("more than one program: " + o.program + ", " + a);
    }
  }
  if (o.program.empty()) usage_error("no program");
  if (!o.trace.empty() && o.engine != "rtl") usage_error("--trace needs --engine rtl");
  return o;
}

void print_regs(const char* name, int first, int count, int per_line, int digits,
                const std::function<std::uint32_t(int)>& value) {
  int shown = 0;
  for (int i = first; i < count; ++i) {
    if (!value(i)) continue;
    std::cout << (shown % per_line ? "  " : "") << name << i << "=" << hex_text(value(i), digits);
    if (++shown % per_line == 0) std::cout << "\n";
  }
  if (shown % per_line) std::cout << "\n";
}

void print_state(const ApuEngine& e) {
  std::cout << "CC " << hex_text(e.cc(), 1) << "  FLAGS " << hex_text(e.flags(), 2) << "\n";
  print_regs("F", 0, kNumFRegs, 6, 6, [&](int i) { return e.freg(i); });
  print_regs("A", 1, kNumARegs, 8, 4, [&](int i) { return std::uint32_t{e.areg(i)}; });
}

int run(const Options& o) {
  const std::vector<Encoded> words = tools::load_program_file(o.program);
  auto engine = tools::make_engine(o.engine, o.trace.empty() ? nullptr : o.trace.c_str());
  ApuDriver drv(*engine);
  drv.load_program(words);
  std::vector<std::vector<std::pair<std::uint16_t, std::uint32_t>>> blocks;
  for (const auto& f : o.data) blocks.push_back(read_data_file(f));
  std::size_t next_block = 0;
  auto hand_over_next = [&] {
    for (const auto& [addr, v] : blocks[next_block]) drv.load_data(addr, &v, 1);
    drv.hand_over_data();
    ++next_block;
  };
  if (!blocks.empty()) hand_over_next();
  drv.hand_over_program();
  drv.start(o.start);
  std::unique_ptr<Profile> profile;
  if (o.profile) {
    profile = std::make_unique<Profile>([&drv](int bank, std::uint16_t pc) { return drv.program_word(bank, pc); });
    drv.set_observer([&](const CycleRecord& r) { profile->add(r); });
  }
  int rc = 0;
  try {
    // The MPU's side of a stream: poll every 16 cycles.
    const auto mpu = [&] {
      if (next_block < blocks.size() && !drv.data_ready()) hand_over_next();
    };
    const std::uint64_t cycles =
        blocks.size() > 1 ? drv.run_until_done(o.max_cycles, mpu, 16) : drv.run_until_done(o.max_cycles);
    std::cout << "apu-run: " << o.program << " on " << o.engine << ": halted after " << cycles << " cycles ("
              << cycles / kApuClockHz * 1e3 << " ms at 4 MHz)\n";
  } catch (const ApuError& e) {
    std::cout << "apu-run: " << o.program << " on " << o.engine << ": " << e.what() << "\n";
    rc = 1;
  }
  print_state(*engine);
  for (const auto& [addr, n] : o.reads) {
    const auto v = drv.read_results(addr, n);
    for (std::size_t i = 0; i < v.size(); ++i)
      std::cout << (i % 8 ? " " : (i ? "\n" : "")) << (i % 8 ? "" : "[" + hex_text(addr + i, 3) + "] ")
                << hex_text(v[i], 6);
    std::cout << "\n";
  }
  if (profile) std::cout << profile->report(o.top);
  return rc;
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  try {
    return run(o);
  } catch (const std::exception& ex) {
    std::cerr << "apu-run: " << ex.what() << "\n";
    return 2;
  }
}
