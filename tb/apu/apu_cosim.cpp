// apu-cosim: two APU engines in lockstep (default ISS vs RTL), stopping at
// the first cycle they disagree on (docs/apu-tools.md).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "apu_coverage.hpp"
#include "apu_driver.hpp"
#include "apu_lockstep.hpp"
#include "apu_random.hpp"
#include "apu_tools.hpp"
#include "atomic_file.hpp"
#include "coverage_aim.hpp"

namespace {

using namespace mc1::apu;
namespace cli = mc1::cmdline;
namespace fc = mc1::cov;

constexpr const char* kDescription =
    "apu-cosim: two APU engines in lockstep, stopping at the first cycle they disagree on.\n"
    "  apu-cosim PROGRAM [--data FILE]... [--max-cycles N] [--engines A,B] [--trace F.fst]\n"
    "  apu-cosim --random N [--seed S] [--first I] [--keep-going] [--max-cycles N] [--engines A,B]\n"
    "            [--weights K=V,...] [--coverage F.json [--waivers FILE] [--close-coverage K]]\n"
    "Runs two APU engines (iss, rtl, icarus; default iss,rtl) cycle by cycle and stops at the first\n"
    "difference in pc, issue, stall reason, bank select, commit, run state or fault, printing\n"
    "cycle, pc, the disassembled word and both values. Several --data files form a stream:\n"
    "the next is handed over when the APU has taken the last. --random checks N generated programs\n"
    "(with their MPU hand-over schedule) from seed S, cases I..I+N-1; --keep-going reports\n"
    "every failing case instead of stopping at the first. icarus is apu_core under Icarus Verilog\n"
    "(a vvp child: the build's apu_icarus_core.vvp, or --icarus-vvp FILE / $MC1_ICARUS_VVP, e.g.\n"
    "the bench compiled with a gate-level netlist); an assertion it prints, an X on a port the\n"
    "cycle uses or the bench ending fails the run like a divergence, with cycle and pc.\n"
    "--weights sets the generator's weights and constraints; --coverage writes the functional\n"
    "coverage of the run (bins and counts, fed by the ISS's cycle records; the ISS must be one\n"
    "of the engines); --close-coverage K aims every next program at the bins still empty (not\n"
    "waived) and stops after K programs that hit no new bin (docs/fp24-verification.md).";

struct Options {
  std::string program, trace, engines = "iss,rtl", icarus_vvp;
  std::vector<std::string> data;
  std::string engine_a = "iss", engine_b = "rtl";
  std::uint64_t max_cycles = 0;  // 0: the default (10 M, or the random case's own)
  long random = -1;              // -1: no --random
  std::uint64_t seed = 1, first = 0;
  bool keep_going = false;
  std::string weights, coverage, waivers;
  long close = 0;           // --close-coverage K (0: off)
  RandomOptions generator;  // --weights
};

// "A,B", each an engine name.
CLI::Validator engine_pair() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        const auto comma = text.find(',');
        const auto& names = tools::engine_names();
        auto known = [&](const std::string& e) { return std::find(names.begin(), names.end(), e) != names.end(); };
        if (comma == std::string::npos || !known(text.substr(0, comma)) || !known(text.substr(comma + 1)))
          return "wants A,B with A and B each iss, rtl or icarus (e.g. iss,rtl), not '" + text + "'";
        return "";
      },
      "A,B");
}

void add_options(CLI::App& app, Options& o) {
  CLI::Option* program = tools::add_program_option(app, o.program);
  tools::add_data_option(app, o.data)->needs(program);
  tools::add_max_cycles_option(app, o.max_cycles, "the cycle limit (default 10 M, or the random case's own)");
  app.add_option("--engines", o.engines, "the two engines")->check(engine_pair())->capture_default_str();
  app.add_option("--icarus-vvp", o.icarus_vvp,
                 "the icarus engine's vvp file (tb/apu/apu_icarus_lockstep_tb.sv compiled with an apu_core;\n"
                 "default $MC1_ICARUS_VVP, else the build's)")
      ->type_name("FILE")->check(cli::input_file());
  app.add_option("--trace", o.trace, "write an FST waveform of the RTL engine (the first, with rtl,rtl) to FILE")
      ->type_name("FILE")->needs(program);
  CLI::Option* random = app.add_option("--random", o.random, "check N generated programs")
                            ->transform(cli::unsigned_in(1, 1'000'000'000))
                            ->excludes(program);
  app.add_option("--seed", o.seed, "the random programs' seed")
      ->transform(cli::unsigned_in(0, UINT64_MAX))
      ->capture_default_str()
      ->needs(random);
  app.add_option("--first", o.first, "the first case index")
      ->transform(cli::unsigned_in(0, UINT64_MAX))
      ->capture_default_str()
      ->needs(random);
  app.add_flag("--keep-going", o.keep_going, "report every failing case, not only the first")->needs(random);
  app.add_option("--weights", o.weights,
                 "generator weights K=V,...: mul add func mem int (ops per word), branch, hazard, fault, late, edge\n"
                 "(percent); delay (cycles), words, fault-kind (a fault name)")
      ->needs(random);
  CLI::Option* coverage =
      app.add_option("--coverage", o.coverage, "write the functional coverage (JSON: bins and counts) to FILE")
          ->type_name("FILE")
          ->needs(random);
  app.add_option("--waivers", o.waivers, "the waiver file (tb/coverage/waivers.txt): bins not aimed at")
      ->type_name("FILE")
      ->check(cli::input_file())
      ->needs(coverage);
  app.add_option("--close-coverage", o.close, "aim at the empty bins; stop after K programs with no new bin")
      ->transform(cli::unsigned_in(1, 1'000'000))
      ->needs(coverage);
}

void check_options(Options& o) {
  if (o.random < 0 && o.program.empty()) throw cli::UsageError("no program and no --random");
  if (o.random > 0 && o.first > UINT64_MAX - static_cast<std::uint64_t>(o.random - 1))
    throw cli::UsageError("--first " + std::to_string(o.first) + " with --random " + std::to_string(o.random) +
                          ": the case indices pass 2^64 - 1");
  const auto comma = o.engines.find(',');
  o.engine_a = o.engines.substr(0, comma);
  o.engine_b = o.engines.substr(comma + 1);
  if (!o.trace.empty() && o.engine_a != "rtl" && o.engine_b != "rtl")
    throw cli::UsageError("--trace needs the rtl engine in --engines");
  if (!o.icarus_vvp.empty() && o.engine_a != "icarus" && o.engine_b != "icarus")
    throw cli::UsageError("--icarus-vvp needs the icarus engine in --engines");
  if (!o.coverage.empty() && o.engine_a != "iss" && o.engine_b != "iss")
    throw cli::UsageError("--coverage needs the iss engine in --engines (it feeds the bins)");
  try {
    o.generator = parse_weights(o.weights);
  } catch (const std::invalid_argument& e) {
    throw cli::UsageError(std::string("--weights: ") + e.what());
  }
}

struct Engines {
  std::unique_ptr<ApuEngine> a, b;
  ApuEngine* both[2];
  Engines(const Options& o, const char* trace)
      : a(tools::make_engine(o.engine_a, o.engine_a == "rtl" ? trace : nullptr, o.icarus_vvp)),
        b(tools::make_engine(o.engine_b, o.engine_b == "rtl" && o.engine_a != "rtl" ? trace : nullptr,
                             o.icarus_vvp)),
        both{a.get(), b.get()} {}
};

bool lockstep_cycles(const Options& o, Lockstep& ls, std::uint64_t max_cycles,
                     const std::function<void()>& mpu, std::uint64_t& cycles, std::uint64_t stalls[kStallKinds],
                     const std::function<void()>& after = {});

// An engine that failed (the icarus engine: an assertion, an X, the bench
// ending), reported as a divergence is: cycle, pc, the word (from the ISS,
// if one of the two is), what. Exit 1, as a divergence.
void report_failure(const Options& o, const Engines& e, const IcarusError& err) {
  const std::string name = dynamic_cast<const IcarusEngine*>(e.a.get()) ? o.engine_a : o.engine_b;
  std::cout << "apu-cosim: " << name << " failed";
  if (err.in_cycle) {
    const Iss* iss = dynamic_cast<const Iss*>(e.a.get());
    if (!iss) iss = dynamic_cast<const Iss*>(e.b.get());
    std::cout << " at cycle " << err.cycle << ", pc " << hex_text(err.pc, 3) << " (bank " << int{err.psel}
              << "): " << (iss ? disassemble(iss->program_word(err.psel, err.pc)) : std::string("(word unknown)"));
  }
  std::cout << "\n  " << err.what() << "\n";
}

// Clocks both until both stop (plus the settle cycles of the HALT word's
// own results, which `cycles` does not count), the MPU acting before every
// cycle. Returns false on a divergence or an engine's failure, after printing it.
bool lockstep_run(const Options& o, const Engines& e, Lockstep& ls, std::uint64_t max_cycles,
                  const std::function<void()>& mpu, std::uint64_t& cycles, std::uint64_t stalls[kStallKinds],
                  const std::function<void()>& after = {}) {
  try {
    return lockstep_cycles(o, ls, max_cycles, mpu, cycles, stalls, after);
  } catch (const IcarusError& err) {
    report_failure(o, e, err);
    return false;
  } catch (const std::runtime_error& err) {
    // Another engine's failure in the run (the verilated core's assertion
    // error names its cycle and pc itself).
    std::cout << "apu-cosim: an engine failed after " << cycles << " cycles\n  " << err.what() << "\n";
    return false;
  }
}

bool lockstep_cycles(const Options& o, Lockstep& ls, std::uint64_t max_cycles,
                     const std::function<void()>& mpu, std::uint64_t& cycles, std::uint64_t stalls[kStallKinds],
                     const std::function<void()>& after) {
  // The settle cycles after both stop are clocked and compared, not
  // counted: `cycles` ends at the HALT's (docs/apu-tools.md "Counting").
  int settle = ApuDriver::kSettleCycles;
  for (cycles = 0; ls.running() ? cycles < max_cycles : settle-- > 0;) {
    const bool counted = ls.running();
    if (mpu) mpu();
    if (auto d = ls.step()) {
      std::cout << "apu-cosim: " << d->report(o.engine_a, o.engine_b);
      return false;
    }
    ++stalls[static_cast<int>(ls.record_a().stall)];
    if (after) after();
    if (counted) ++cycles;
  }
  if (ls.running()) {
    std::cout << "apu-cosim: both engines still running after " << max_cycles << " cycles (pc "
              << hex_text(ls.record_a().pc, 3) << ", stall " << stall_name(ls.record_a().stall)
              << "); no divergence so far\n";
    return false;
  }
  if (auto d = ls.compare_state()) {
    std::cout << "apu-cosim: final state differs\n" << d->report(o.engine_a, o.engine_b);
    return false;
  }
  return true;
}

// fst: the file the RTL engine writes --trace's waveform to (its staged
// temporary; "" without --trace).
int run_program(const Options& o, const std::string& fst) {
  const std::vector<Encoded> words = tools::load_program_file(o.program);
  std::vector<std::vector<std::pair<std::uint16_t, std::uint32_t>>> blocks;
  for (const auto& f : o.data) blocks.push_back(read_data_file(f));
  Engines e(o, fst.empty() ? nullptr : fst.c_str());
  std::size_t next = 0;
  auto hand_over_next = [&] {
    for (ApuEngine* eng : e.both) {
      for (const auto& [addr, v] : blocks[next]) eng->write_data(addr, v);
      eng->hand_over_data();
    }
    ++next;
  };
  for (ApuEngine* eng : e.both) {
    for (std::size_t i = 0; i < words.size(); ++i) eng->write_program(static_cast<std::uint16_t>(i), words[i]);
    eng->hand_over_program();
  }
  if (!blocks.empty()) hand_over_next();
  for (ApuEngine* eng : e.both) eng->start(0);
  Lockstep ls(*e.a, *e.b);
  std::uint64_t cycles = 0, stalls[kStallKinds] = {};
  const auto mpu = [&] {
    if (next < blocks.size() && !e.a->data_ready()) hand_over_next();
  };
  const bool ok = lockstep_run(o, e, ls, o.max_cycles ? o.max_cycles : 10'000'000, mpu, cycles, stalls);
  if (!ok) return 1;
  std::cout << "apu-cosim: " << o.engine_a << " and " << o.engine_b << " agree on " << cycles << " cycles; "
            << run_state_name(e.a->state());
  if (e.a->state() == RunState::Faulted) std::cout << " (" << fault_name(e.a->fault()) << ")";
  std::cout << "\n";
  return 0;
}

// What the random cases added up to.
struct RandomTotals {
  std::uint64_t cycles = 0, stalls[kStallKinds] = {}, halted = 0, faulted = 0, handovers = 0, failed = 0, run = 0;
};

// The coverage of a random run (--coverage): the collector, fed by the ISS.
struct CoverageRun {
  fc::ApuCoverage bins;
  std::unique_ptr<fc::CoverageAim> aim;  // --close-coverage
};

const Iss* find_iss(const Engines& e) {
  const Iss* iss = dynamic_cast<const Iss*>(e.a.get());
  return iss ? iss : dynamic_cast<const Iss*>(e.b.get());
}

// Case `index` with generator options `opt`; false (after printing why) if
// the engines disagree or did not do what the generator planned.
bool random_case(const Options& o, std::uint64_t index, const RandomOptions& opt, fc::ApuCoverage* cov,
                 RandomTotals& t) {
  const RandomCase c = make_random_case(case_seed(o.seed, index), opt);
  Engines e(o, nullptr);
  RandomMpu mpu(c);
  const Iss* iss = find_iss(e);
  if (cov) {
    cov->start();
    cov->handover(false, RunState::Idle, false);  // boot: both banks before the start
    cov->handover(true, RunState::Idle, false);
  }
  mpu.boot(e.both, 2);
  Lockstep ls(*e.a, *e.b);
  const CycleRecord& rec = iss == e.a.get() ? ls.record_a() : ls.record_b();
  const auto before = [&] {
    const bool data = e.a->data_ready(), program = e.a->program_ready();
    mpu.before_cycle(e.both, 2);
    if (!cov) return;
    const bool waiting = ls.record_a().stall == Stall::Bank;
    if (!data && e.a->data_ready()) cov->handover(false, e.a->state(), waiting);
    if (!program && e.a->program_ready()) cov->handover(true, e.a->state(), waiting);
    cov->before_cycle(*iss);
  };
  const auto after = [&] {
    if (cov) cov->after_cycle(*iss, rec);
  };
  std::uint64_t cycles = 0;
  const bool ok = lockstep_run(o, e, ls, o.max_cycles ? o.max_cycles : c.max_cycles, before, cycles, t.stalls, after);
  const auto rerun = [&] {
    std::cout << "  case " << index << " of seed " << o.seed << ": " << c.describe() << "\n"
              << "  rerun: apu-cosim --random 1 --seed " << o.seed << " --first " << index << " --engines "
              << o.engine_a << "," << o.engine_b << " --weights " << weights_text(opt) << "\n";
  };
  if (!ok) return rerun(), false;
  // Both agree; they must also have done what the generator planned.
  const bool as_planned = c.planned_fault == Fault::None
                              ? e.a->state() == RunState::Halted
                              : e.a->state() == RunState::Faulted && e.a->fault() == c.planned_fault;
  if (!as_planned) {
    std::cout << "apu-cosim: both engines end " << run_state_name(e.a->state()) << " (" << fault_name(e.a->fault())
              << ") at cycle " << e.a->cycle() << ", pc " << hex_text(ls.record_a().pc, 3)
              << ", but the program was made to end in "
              << (c.planned_fault == Fault::None ? "halt" : fault_name(c.planned_fault)) << "\n";
    return rerun(), false;
  }
  if (cov) cov->end(*iss, rec);
  t.cycles += cycles;
  (e.a->state() == RunState::Halted ? t.halted : t.faulted) += 1;
  t.handovers += static_cast<std::uint64_t>(mpu.data_handovers() + mpu.program_handovers());
  return true;
}

std::size_t bins_hit(const fc::Bins& bins) {
  std::size_t n = 0;
  for (const auto& [name, count] : bins.counts()) n += count != 0;
  return n;
}

// --coverage: the file, and a line of figures.
void report_coverage(const Options& o, const CoverageRun& run) {
  const fc::Bins& bins = run.bins.bins();
  mc1::write_file_atomically(o.coverage, bins.json());
  std::size_t waived = 0;
  std::vector<fc::Waiver> waivers;
  if (!o.waivers.empty()) waivers = fc::read_waivers(o.waivers);
  for (const auto& [name, count] : bins.counts()) waived += count == 0 && fc::waiver_for(waivers, name);
  std::cout << "apu-cosim: functional coverage: " << bins_hit(bins) << " of " << bins.size() << " bins hit, "
            << waived << " of the others waived; " << o.coverage << "\n";
}

int run_random(const Options& o) {
  RandomTotals t;
  std::unique_ptr<CoverageRun> cov;
  if (!o.coverage.empty()) {
    cov = std::make_unique<CoverageRun>();
    if (o.close) cov->aim = std::make_unique<fc::CoverageAim>(
                     o.generator, o.waivers.empty() ? std::vector<fc::Waiver>{} : fc::read_waivers(o.waivers));
  }
  const auto t0 = std::chrono::steady_clock::now();
  long quiet = 0;  // programs since the last new bin (--close-coverage)
  for (long n = 0; n < o.random && (!o.close || quiet < o.close); ++n) {
    const std::uint64_t index = o.first + static_cast<std::uint64_t>(n);
    const std::size_t hit = cov ? bins_hit(cov->bins.bins()) : 0;
    const RandomOptions opt = cov && cov->aim ? cov->aim->next(cov->bins.bins(), index) : o.generator;
    ++t.run;
    if (!random_case(o, index, opt, cov ? &cov->bins : nullptr, t)) {
      if (!o.keep_going) return 1;
      ++t.failed;
      continue;
    }
    if (cov) quiet = bins_hit(cov->bins.bins()) > hit ? 0 : quiet + 1;
    if ((n + 1) % 100 == 0 || n + 1 == o.random)
      std::cerr << "apu-cosim: " << (n + 1) << "/" << o.random << " cases, " << t.cycles << " cycles, "
                << cli::progress_times(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
                                       static_cast<double>(n + 1) / static_cast<double>(o.random))
                << "\n";
  }
  if (cov) report_coverage(o, *cov);
  if (t.failed) {
    std::cout << "apu-cosim: " << t.failed << " of " << t.run << " random programs failed\n";
    return 1;
  }
  std::cout << "apu-cosim: " << t.run << " random programs (seed " << o.seed << "), " << o.engine_a << " and "
            << o.engine_b << " agree on " << t.cycles << " cycles; " << t.halted << " halted, " << t.faulted
            << " faulted as planned; " << t.handovers << " MPU hand-overs\n  stall cycles:";
  for (int s = 1; s < kStallKinds; ++s) std::cout << " " << stall_name(static_cast<Stall>(s)) << " " << t.stalls[s];
  std::cout << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{kDescription, "apu-cosim"};
  cli::conventions(app, "Exit status: 0 all agree; 1 divergence; 2 usage or input error.");
  Options o;
  add_options(app, o);
  cli::Files files;  // the file options, checked together after parsing
  files.input(app.get_option("PROGRAM"), "the program");
  files.input(app.get_option("--data"), "the data file");
  files.output(app.get_option("--trace"));
  files.output(app.get_option("--coverage"));
  if (auto rc = cli::parse(app, argc, argv)) return *rc;
  try {
    check_options(o);
    if (!o.program.empty()) tools::add_included_files(o.program, files);
    files.check();
    if (o.random >= 0) return cli::flush_stdout("apu-cosim", run_random(o));
    // The waveform is staged: the engine writes it under a temporary name,
    // put in place once the engine has closed it (run_program() returned),
    // and only when the engines agreed (a failed run leaves no waveform).
    std::optional<mc1::StagedFile> fst;
    if (!o.trace.empty()) fst.emplace(cli::writer_output("--trace", o.trace));
    const int rc = run_program(o, fst ? fst->temp() : "");
    if (fst && rc == 0) fst->commit();
    return cli::flush_stdout("apu-cosim", rc);
  } catch (const cli::UsageError& e) {
    return cli::usage_error(app, e.what());
  } catch (const std::exception& ex) {
    std::cerr << "apu-cosim: " << ex.what() << "\n";
    return cli::kExitUsage;
  }
}
