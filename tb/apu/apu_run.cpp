// apu-run: runs one APU program on the ISS or the RTL core through the MPU
// driver, like firmware would, and prints the outcome, the registers and
// (--profile) a cycle profile (docs/apu-tools.md).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "apu_driver.hpp"
#include "atomic_file.hpp"
#include "disasm.hpp"
#include "fp24.hpp"
#include "fp24_convert.hpp"
#include "apu_lockstep.hpp"
#include "apu_profile.hpp"
#include "apu_stall_profile.hpp"
#include "apu_trace_files.hpp"
#include "apu_tools.hpp"

namespace {

using namespace mc1::apu;
namespace cli = mc1::cmdline;

constexpr const char* kDescription =
    "apu-run: runs one APU program on the ISS or the RTL core through the MPU driver.\n"
    "Loads the program (and data) into the MPU's banks, hands them over, starts the APU and waits\n"
    "for HALT. Prints the cycles (start to the HALT's issue, docs/apu-tools.md \"Counting\") and\n"
    "the registers that are not zero, decoded (CC and FLAGS by name, F as FP24, A as integers);\n"
    "--read prints data words the MPU sees after the run (the bank the APU left with its last\n"
    "SWAPD) in hex and decoded (FP24, or an integer where FP24 reads a flushed zero); --profile\n"
    "prints unit utilization, stalls by reason and the top N stalling words.";

struct Options {
  std::string program, trace, engine = "iss";
  std::vector<std::string> data, read_texts;
  bool profile = false;
  std::string profile_json;
  int top = 10;
  std::uint64_t max_cycles = 100'000'000;
  std::uint16_t start = 0;
  std::vector<std::pair<std::uint16_t, std::uint16_t>> reads;
};

// ADDR:COUNT inside the 4096-word data bank.
std::pair<std::uint16_t, std::uint16_t> parse_read(const std::string& text) {
  const auto colon = text.find(':');
  if (colon == std::string::npos) throw cli::UsageError("--read wants ADDR:COUNT, not '" + text + "'");
  const std::uint64_t addr = cli::parse_unsigned("--read " + text, text.substr(0, colon), 0, kDataWords - 1);
  const std::uint64_t n = cli::parse_unsigned("--read " + text, text.substr(colon + 1), 1, kDataWords);
  if (addr + n > static_cast<std::uint64_t>(kDataWords))
    throw cli::UsageError("--read " + text + " goes past word " + std::to_string(kDataWords - 1));
  return {static_cast<std::uint16_t>(addr), static_cast<std::uint16_t>(n)};
}

// The tool is the MPU of the run (it loads the banks and hands them over, at
// once, polling every 16 cycles): what it does in a cycle, for the
// waveform's TOP.mc1.mpu_doing and the stall profile's BANK stalls, in the
// numbers of nc::MpuDoing (hw/nc/mpu_activity.hpp) with its own names.
enum ToolDoing : std::uint8_t { kPoll = 1, kWaitSwap = 8, kWaitHalt = 9 };
const MpuFilters& tool_filters() {
  static const MpuFilters f{
      "# what apu-run, the MPU of the run, does (GTKWave translate filter for TOP.mc1.mpu_doing)\n"
      "0 idle\n1 poll\n8 wait_swap\n9 wait_halt\n",
      "# apu-run has no firmware steps (TOP.mc1.mpu_step)\n0000 -\n"};
  return f;
}
// poll: the next bank goes over at the next poll; wait_swap: a bank handed
// over, not yet taken; wait_halt: no bank left to hand over.
std::string tool_doing_name(unsigned d) {
  return d == kPoll ? "poll" : d == kWaitSwap ? "wait_swap" : d == kWaitHalt ? "wait_halt" : "idle";
}

// Every file option is declared in `files` (cmdline::Files), checked after parsing.
void add_options(CLI::App& app, Options& o, cli::Files& files) {
  files.input(tools::add_program_option(app, o.program)->required(), "the program");
  app.add_option("--engine", o.engine, "the engine")
      ->check(CLI::IsMember(tools::engine_names()))
      ->capture_default_str();
  files.input(tools::add_data_option(app, o.data), "the data file");
  files.output(app.add_option("--trace", o.trace,
                              "write an FST waveform of the RTL core to FILE (the run is on the RTL core,\n"
                              "whatever --engine says), and its GTKWave save file and filters beside it\n"
                              "(FILE.gtkw, FILE.kpc.txt, ...)")
                   ->type_name("FILE"),
               trace_side_suffixes());
  app.add_flag("--profile", o.profile, "print the cycle profile");
  files.output(app.add_option("--profile-json", o.profile_json, "also write the profile as JSON to FILE (docs/apu-tools.md)")
                   ->type_name("FILE"));
  app.add_option("--top", o.top, "stalling words the profile lists")
      ->transform(cli::unsigned_in(0, 2 * kProgramWords))
      ->capture_default_str();
  app.add_option("--read", o.read_texts, "print COUNT data words from ADDR after the run")
      ->type_name("ADDR:COUNT")
      ->allow_extra_args(false);
  tools::add_max_cycles_option(app, o.max_cycles, "the cycle limit (exit 1 when reached)")->capture_default_str();
  app.add_option("--start", o.start, "the pc to start at")
      ->transform(cli::unsigned_in(0, kProgramWords - 1))
      ->capture_default_str();
}

// The checks CLI11 cannot make alone.
void check_options(Options& o) {
  for (const std::string& r : o.read_texts) o.reads.push_back(parse_read(r));
  // The waveform is the RTL core's: --trace runs on it, as mc1 render's
  // traced NC does, and says so when another engine was asked for.
  if (!o.trace.empty() && o.engine != "rtl") {
    std::cerr << "apu-run: --trace: running on the RTL core (the waveform is of it), not " << o.engine << "\n";
    o.engine = "rtl";
  }
}

// A data word as a person reads it: FP24's value, or, for a word FP24 reads
// as a flushed zero (exponent 0, a fraction: a count or an address the
// kernels keep as an integer), the integer.
std::string word_value(std::uint32_t w) {
  if ((w & 0x7F0000) == 0 && (w & 0xFFFF)) return "int " + std::to_string(w & 0xFFFF);
  return mc1::fp24::fp24_decimal(w);
}

// CC and FLAGS by name: "LT|UN", "NV|NX"; "-" for none.
std::string bit_names(unsigned v, std::initializer_list<std::pair<unsigned, const char*>> names) {
  std::string s;
  for (const auto& [bit, name] : names)
    if (v & bit) s += (s.empty() ? "" : "|") + std::string(name);
  return s.empty() ? "-" : s;
}

void print_regs(const char* name, int first, int count, int per_line,
                const std::function<std::uint32_t(int)>& value, const std::function<std::string(std::uint32_t)>& text) {
  int shown = 0;
  for (int i = first; i < count; ++i) {
    if (!value(i)) continue;
    std::cout << (shown % per_line ? "  " : "") << name << i << "=" << text(value(i));
    if (++shown % per_line == 0) std::cout << "\n";
  }
  if (shown % per_line) std::cout << "\n";
}

// The registers decoded: CC and FLAGS by name, F registers as FP24, A
// registers (16 bits) unsigned and, when the sign bit is set, signed.
void print_state(const ApuEngine& e) {
  using namespace mc1::fp24;
  std::cout << "CC " << hex_text(e.cc(), 1) << " (" << bit_names(e.cc(), {{kLT, "LT"}, {kEQ, "EQ"}, {kGT, "GT"}, {kUN, "UN"}})
            << ")  FLAGS " << hex_text(e.flags(), 2) << " ("
            << bit_names(e.flags(), {{kNV, "NV"}, {kDZ, "DZ"}, {kOF, "OF"}, {kUF, "UF"}, {kNX, "NX"}}) << ")\n";
  print_regs("F", 0, kNumFRegs, 4, [&](int i) { return e.freg(i); },
             [](std::uint32_t v) { return hex_text(v, 6) + " (" + mc1::fp24::fp24_decimal(v) + ")"; });
  print_regs("A", 1, kNumARegs, 6, [&](int i) { return std::uint32_t{e.areg(i)}; }, [](std::uint32_t v) {
    return hex_text(v, 4) + " (" + std::to_string(v) +
           (v & 0x8000 ? ", " + std::to_string(static_cast<int>(v) - 0x10000) : std::string()) + ")";
  });
}

// --read's words: four a line, each in hex and decoded (word_value).
void print_words(std::uint16_t addr, const std::vector<std::uint32_t>& v) {
  for (std::size_t i = 0; i < v.size(); ++i) {
    const std::string cell = hex_text(v[i], 6) + " (" + word_value(v[i]) + ")";
    std::cout << (i % 4 ? "  " : (i ? "\n" : "")) << (i % 4 ? "" : "[" + hex_text(addr + i, 3) + "] ") << cell
              << std::string(i % 4 != 3 && i + 1 < v.size() && cell.size() < 22 ? 22 - cell.size() : 0, ' ');
  }
  std::cout << "\n";
}

// Runs `put`, an output's write or commit (host/common/atomic_file.hpp);
// false, said on stderr, when it throws.
template <class Put>
bool output_ok(const std::string& option, Put put) {
  try {
    put();
    return true;
  } catch (const std::exception& e) {
    std::cerr << "apu-run: " << option << ": " << e.what() << "\n";
    return false;
  }
}

// An output file staged in `out`, to be committed with the others once the
// run has succeeded; false, said on stderr, when it could not be written.
bool stage_output(std::vector<mc1::StagedFile>& out, const std::string& option, const std::string& path,
                  const std::string& text) {
  return output_ok(option, [&] { out.emplace_back(path, text); });
}

// The tool's side in the waveform (TOP.mc1.mpu_*): what it does, and the
// data blocks it has handed over so far (mpu_detail).
void trace_tool(ApuEngine& engine, std::function<std::uint8_t()> doing, const std::size_t& handed) {
  engine.trace_mpu([doing = std::move(doing), &handed](std::uint64_t) {
    ApuEngine::MpuTraceInputs in;
    in.doing = doing();
    in.detail = static_cast<std::uint32_t>(handed);
    return in;
  });
}

// fst: the file the RTL engine writes --trace's waveform to (its staged
// temporary; "" without --trace). The outputs are staged in `out`: a run
// that fails leaves none of them.
int run(const Options& o, const std::string& fst, std::vector<mc1::StagedFile>& out) {
  const std::vector<Encoded> words = tools::load_program_file(o.program);
  auto engine = tools::make_engine(o.engine, fst.empty() ? nullptr : fst.c_str());
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
  // The program is kernel 1 (TOP.mc1.kernel_id in the waveform, the stall profile's kernel).
  KernelTable kernels;
  kernels.add(o.program, words);
  drv.on_hand_over([&](int bank, const std::vector<Encoded>&) { engine->trace_kernel(bank, 1); });
  drv.hand_over_program();
  drv.start(o.start);
  std::unique_ptr<Profile> profile;
  if (o.profile || !o.profile_json.empty())
    profile = std::make_unique<Profile>([&drv](int bank, std::uint16_t pc) { return drv.program_word(bank, pc); });
  // The stall profile: for --profile-json, and for a trace's markers.
  StallProfile stalls;
  stalls.set_mpu_names(tool_doing_name);
  // What the tool does in a cycle: waits for the APU to take the bank it
  // handed over, or for the next poll to hand over the next, or for HALT.
  const std::function<std::uint8_t()> doing = [&] {
    return drv.data_ready() ? kWaitSwap : next_block < blocks.size() ? kPoll : kWaitHalt;
  };
  trace_tool(*engine, doing, next_block);
  if (profile || !o.trace.empty())
    drv.set_observer([&](const CycleRecord& r) {
      if (profile) profile->add(r);
      const bool bank = !r.issued && r.stall == Stall::Bank;
      stalls.add(1, 1, r, engine->time_of(r.cycle), bank ? doing() : StallProfile::kNoMpu);
    });
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
  for (const auto& [addr, n] : o.reads) print_words(addr, drv.read_results(addr, n));
  stalls.finish();
  if (!o.trace.empty()) {
    const std::string markers = stalls.nc_totals(1).cycles ? stalls.gtkw_markers(kernels, 1, 26) : "";
    for (const auto& [path, text] : trace_side_files(o.trace, kernels, markers, "apu-run --trace", tool_filters()))
      if (!stage_output(out, "--trace", path, text)) rc = 1;
  }
  if (profile && o.profile) std::cout << profile->report(o.top);
  if (profile && !o.profile_json.empty()) {
    std::string extra = ", \"program\": " + json_quote(o.program) + ", \"engine\": " + json_quote(o.engine) + ", \"unit_ops\": {";
    for (int u = 0; u < kFpUnits; ++u)
      extra += std::string(u ? ", " : "") + "\"" + unit_name(u) + "\": " + std::to_string(profile->unit_ops(u));
    extra += "}";
    if (!stage_output(out, "--profile-json", o.profile_json, stalls.json(kernels, "apu-run", extra))) rc = 1;
  }
  return rc;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{kDescription, "apu-run"};
  cli::conventions(app, "Exit status: 0 halted; 1 fault or cycle limit; 2 usage or input error.");
  Options o;
  cli::Files files;
  add_options(app, o, files);
  if (auto rc = cli::parse(app, argc, argv)) return *rc;
  try {
    check_options(o);
    tools::add_included_files(o.program, files);
    files.check();  // no output on an input or another output; each writable
    // The waveform is staged: the engine writes it under a temporary name,
    // put in place with the other outputs once the engine has closed it
    // (run() returned), and only if the run succeeded.
    std::optional<mc1::StagedFile> fst;
    if (!o.trace.empty()) fst.emplace(cli::writer_output("--trace", o.trace));
    std::vector<mc1::StagedFile> out;
    int rc = run(o, fst ? fst->temp() : "", out);
    // The waveform first: a writer's FST that is not whole (a full disk) is
    // refused at its commit, and then no side file of it goes in place.
    if (rc == 0 && !output_ok("the outputs", [&] {
          if (fst) fst->commit();
          for (mc1::StagedFile& f : out) f.commit();
        }))
      rc = 1;
    return cli::flush_stdout("apu-run", rc);
  } catch (const cli::UsageError& e) {
    return cli::usage_error(app, e.what());
  } catch (const std::exception& ex) {
    std::cerr << "apu-run: " << ex.what() << "\n";
    return cli::kExitUsage;
  }
}
