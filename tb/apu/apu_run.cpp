// apu-run: runs one APU program on the ISS or the RTL core through the MPU
// driver, like firmware would, and prints the outcome, the registers and
// (--profile) a cycle profile (docs/apu-tools.md).
#include <cstdlib>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "apu_driver.hpp"
#include "atomic_file.hpp"
#include "disasm.hpp"
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
    "for HALT. Prints cycles and the registers that are not zero; --read prints data words the\n"
    "MPU sees after the run (the bank the APU left with its last SWAPD); --profile prints unit\n"
    "utilization, stalls by reason and the top N stalling words.";

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

// Every file option is declared in `files` (cmdline::Files), checked after parsing.
void add_options(CLI::App& app, Options& o, cli::Files& files) {
  files.input(tools::add_program_option(app, o.program)->required(), "the program");
  app.add_option("--engine", o.engine, "the engine")
      ->check(CLI::IsMember(tools::engine_names()))
      ->capture_default_str();
  files.input(tools::add_data_option(app, o.data), "the data file");
  files.output(app.add_option("--trace", o.trace,
                              "rtl only: write an FST waveform of the core to FILE, and its GTKWave\n"
                              "save file and filters beside it (FILE.gtkw, FILE.kpc.txt, ...)")
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
  if (!o.trace.empty() && o.engine != "rtl") throw cli::UsageError("--trace needs --engine rtl");
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
  if (profile || !o.trace.empty())
    drv.set_observer([&](const CycleRecord& r) {
      if (profile) profile->add(r);
      stalls.add(1, 1, r, engine->time_of(r.cycle));
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
  for (const auto& [addr, n] : o.reads) {
    const auto v = drv.read_results(addr, n);
    for (std::size_t i = 0; i < v.size(); ++i)
      std::cout << (i % 8 ? " " : (i ? "\n" : "")) << (i % 8 ? "" : "[" + hex_text(addr + i, 3) + "] ")
                << hex_text(v[i], 6);
    std::cout << "\n";
  }
  stalls.finish();
  if (!o.trace.empty()) {
    const std::string markers = stalls.nc_totals(1).cycles ? stalls.gtkw_markers(kernels, 1, 26) : "";
    for (const auto& [path, text] : trace_side_files(o.trace, kernels, markers, "apu-run --trace"))
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
    if (rc == 0 && fst) out.push_back(std::move(*fst));
    if (rc == 0 && !output_ok("the outputs", [&] { for (mc1::StagedFile& f : out) f.commit(); })) rc = 1;
    return cli::flush_stdout("apu-run", rc);
  } catch (const cli::UsageError& e) {
    return cli::usage_error(app, e.what());
  } catch (const std::exception& ex) {
    std::cerr << "apu-run: " << ex.what() << "\n";
    return cli::kExitUsage;
  }
}
