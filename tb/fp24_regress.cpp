// fp24-regress: the FP24 regression (docs/fp24-verification.md).
// One-operand ops on every encoding; two-operand ops on a TestFloat-level-2
// style structured set plus seeded random pairs; three engines compared:
// verilated RTL == C++ model bit for bit, model == MPFR oracle (correctly
// rounded ops) or faithful with measured ulp error (SIN/COS).
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstring>
#include <exception>
#include <fstream>
#include <iostream>
#include <memory>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>
#include <tuple>
#include <vector>

#include "cmdline.hpp"
#include "fp24.hpp"
#include "fp24_golden.hpp"
#include "fp24_oracle.hpp"
#include "fp24_regress_merge.hpp"
#include "fp24_rtl.hpp"
#include "fp24_vectors.hpp"
#include "json.hpp"
#include "shard_report.hpp"

namespace {

using namespace mc1::fp24;
using namespace mc1::fp24::tb;
using Clock = std::chrono::steady_clock;
namespace cli = mc1::cmdline;

constexpr const char* kDescription =
    "fp24-regress: the FP24 regression (docs/fp24-verification.md).\n"
    "Default run: recip sqrt sin cos fix neg abs on all 2^24 encodings, float on\n"
    "all 2^16 integers, add sub mul cmp on a structured set (exponent table x\n"
    "significand patterns x signs, all pairs) plus random pairs; RTL vs model\n"
    "and model vs MPFR oracle. Exit status 0 only if everything matches and\n"
    "SIN/COS are faithful.\n"
    "--vectors FILE runs a user's file instead: `op a [b]` lines, or golden\n"
    "`op a [b] result flags` lines (as fp24-run --check reads them), each on\n"
    "the RTL, the model and the oracle, and golden lines also against their\n"
    "expected result; failures name FILE:LINE.\n"
    "--shard K/N runs the K-th of N disjoint slices of the same run (each\n"
    "vector set of each op cut in N contiguous ranges); --merge REPORT.json...\n"
    "combines the --json reports of all N shards into the report of the whole\n"
    "run (docs/fp24-verification.md, tools/slurm/).";

constexpr std::uint32_t kChunk = 1u << 16;  // vectors per job
constexpr std::uint64_t kLongRandom = 1000000000;

struct Options {
  std::vector<Op> ops;
  bool rtl = true;
  bool oracle = true;
  bool long_run = false;
  bool structured = true;          // --no-structured clears
  bool exhaustive_pairs = false;   // two-operand ops on all 2^48 pairs
  std::uint64_t shard = 1, shards = 1;  // --shard K/N
  std::vector<std::string> merge;  // --merge REPORT.json...
  std::uint64_t random = 10000000;
  std::uint64_t seed = 1;
  unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  unsigned show = 5;
  std::string text, json;
  std::string vectors;        // --vectors FILE
  std::vector<Golden> user;   // its lines
};

// ---- command line ----------------------------------------------------------------

std::vector<Op> all_ops() {
  std::vector<Op> ops;
  for (int i = 0; i < kOpCount; ++i) ops.push_back(static_cast<Op>(i));
  return ops;
}

std::vector<Op> parse_ops(const std::string& list) {
  std::vector<Op> ops;
  std::stringstream s(list);
  std::string name;
  while (std::getline(s, name, ',')) {
    const std::optional<Op> op = op_from_name(name);
    if (!op) throw cli::UsageError("--ops: unknown op '" + name + "'");
    if (std::find(ops.begin(), ops.end(), *op) == ops.end()) ops.push_back(*op);
  }
  if (ops.empty()) throw cli::UsageError("--ops: empty list");
  return ops;
}

// The file options are declared in `files` (cmdline::Files), checked after parsing.
void add_options(CLI::App& app, Options& o, std::string& ops, std::string& shard_text, cli::Files& files) {
  app.add_option("--ops", ops, "comma-separated ops to run (default: all 12)")->type_name("LIST");
  app.add_flag("--no-rtl{false}", o.rtl, "skip the verilated RTL");
  app.add_flag("--no-oracle{false}", o.oracle, "skip the MPFR oracle");
  app.add_option("--random", o.random, "random pairs per two-operand op")
      ->transform(cli::unsigned_in(0, UINT64_MAX))
      ->capture_default_str();
  app.add_option("--seed", o.seed, "random seed; a run is reproducible from it")
      ->transform(cli::unsigned_in(0, UINT64_MAX))
      ->capture_default_str();
  app.add_flag("--long", o.long_run,
               "add the long sweep: mul on all 2^32 significand pairs at\n"
               "exponents (63, 63), and random pairs raised to >= 10^9");
  app.add_flag("--no-structured{false}", o.structured, "two-operand ops: skip the structured set");
  app.add_flag("--exhaustive-pairs", o.exhaustive_pairs,
               "two-operand ops on all 2^48 operand pairs instead of the\n"
               "structured and random sets (run it as shards: --shard)");
  app.add_option("--shard", shard_text, "run slice K of N (1 <= K <= N); the N slices together\n"
                                        "cover the unsharded run exactly once")
      ->type_name("K/N");
  files.input(app.add_option("--merge", o.merge, "merge the --json reports of shards 1..N of one run (nothing is run)")
                  ->type_name("REPORT.json...")
                  ->check(cli::input_file()),
              "the report");
  app.add_option("--threads", o.threads, "worker threads (default: all cores)")
      ->transform(cli::unsigned_in(1, 1024));
  app.add_option("--show", o.show, "failing vectors listed per op and kind")
      ->transform(cli::unsigned_in(0, 1000000))
      ->capture_default_str();
  files.output(app.add_option("--text", o.text, "also write the text report to FILE")->type_name("FILE"));
  files.output(app.add_option("--json", o.json, "write the report as JSON to FILE")->type_name("FILE"));
  files.input(app.add_option("--vectors", o.vectors, "run the vectors (or golden lines) of FILE instead of the built-in sets")
                  ->type_name("FILE")
                  ->check(cli::input_file()),
              "the vectors");
}

// A --vectors run has no built-in sets to shape: the options that shape
// them with it are usage errors naming both ("--vectors excludes --long").
void add_exclusions(CLI::App& app) {
  CLI::Option* vectors = app.get_option("--vectors");
  for (const char* name : {"--long", "--exhaustive-pairs", "--random", "--no-structured", "--seed"})
    vectors->excludes(app.get_option(name));
}

// "K/N" with 1 <= K <= N < 2^32.
void parse_shard(const std::string& text, Options& o) {
  std::tie(o.shard, o.shards) = mc1::shard::parse_shard("--shard", text);
}

// The --vectors file, every line checked before anything runs; the ops it
// uses (those of --ops only, if given) become the run's ops.
void read_user_vectors(Options& o, bool ops_given) {
  std::ifstream in(o.vectors, std::ios::binary);
  if (!in) throw cli::UsageError("--vectors: " + o.vectors + ": cannot open");
  o.user = read_golden(in, o.vectors, true);  // lines of 4096 bytes, 1 GiB at most (fp24_vectors.hpp)
  if (in.bad()) throw cli::UsageError("--vectors: " + o.vectors + ": read error");
  std::vector<Op> used;
  for (Op op : o.ops)
    for (const Golden& g : o.user)
      if (g.vector.op == op && (used.empty() || used.back() != op)) used.push_back(op);
  if (!ops_given && used.empty()) throw cli::UsageError("--vectors: " + o.vectors + ": no vectors");
  o.ops = used;
}

// ---- vectors ---------------------------------------------------------------------

// TestFloat level 2 style operands: exponents at and around the format's
// edges (zero/DAZ, smallest normals, 1.0, the alignment-shift limits of the
// adder around 63 +- 17, largest normals, inf/NaN) x significand patterns.
std::vector<Bits> structured_values() {
  static const int kExps[] = {0,  1,  2,  3,  44, 45, 46, 47, 61,  62,  63,  64,  65,
                              66, 79, 80, 81, 82, 94, 95, 124, 125, 126, 127};
  std::vector<Bits> fracs = {0x0000, 0x0001, 0x0002, 0x0003, 0xFFFF, 0xFFFE, 0xFFFD, 0x8000, 0x7FFF,
                             0x8001, 0xAAAA, 0x5555, 0xC000, 0x4000, 0x3FFF, 0xBFFF, 0x0F0F, 0xF0F0};
  for (int k = 0; k < 16; ++k) {
    fracs.push_back(Bits(1) << k);                     // single bits
    fracs.push_back((Bits(1) << k) - 1);               // ones below bit k
    fracs.push_back((0xFFFFu << k) & 0xFFFF);          // ones from bit k up
    fracs.push_back(~(Bits(1) << k) & 0xFFFF);         // all ones but one
  }
  std::sort(fracs.begin(), fracs.end());
  fracs.erase(std::unique(fracs.begin(), fracs.end()), fracs.end());
  std::vector<Bits> values;
  for (Bits sign : {Bits(0), kSignBit})
    for (int e : kExps)
      for (Bits f : fracs) values.push_back(sign | Bits(e) << 16 | f);
  return values;
}

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// Random pair number `index` of op: a pure function of (seed, op, index), so
// results do not depend on threads or chunking. Half the pairs are uniform
// encodings; half put b's exponent within +-24 of a's, where the adder's
// alignment, cancellation and carry paths are.
void random_pair(std::uint64_t seed, Op op, std::uint64_t index, Bits* a, Bits* b) {
  const std::uint64_t h = splitmix64(splitmix64(seed * 64 + std::uint64_t(op)) ^ index);
  *a = Bits(h) & 0xFFFFFF;
  const Bits r = Bits(h >> 24) & 0xFFFFFF;
  if ((h >> 63) == 0) {
    *b = r;
    return;
  }
  const int ea = int((*a >> 16) & 0x7F);
  const int eb = std::clamp(ea + int((h >> 48) % 49) - 24, 0, 127);
  *b = (r & (kSignBit | 0xFFFF)) | Bits(eb) << 16;
}

enum class Source { Exhaustive, Structured, Random, SigSweep, AllPairs, File };

struct Job {
  Op op;
  Source source;
  std::uint64_t first;
  std::uint32_t count;
};

struct VectorSet {
  std::vector<Bits> structured = structured_values();
  std::uint64_t seed = 1;
  std::vector<std::vector<const Golden*>> file = std::vector<std::vector<const Golden*>>(kOpCount);  // by op

  void fill(const Job& j, Bits* a, Bits* b) const {
    const std::uint64_t n = structured.size();
    for (std::uint32_t i = 0; i < j.count; ++i) {
      const std::uint64_t k = j.first + i;
      switch (j.source) {
        case Source::Exhaustive: a[i] = Bits(k); b[i] = 0; break;
        case Source::Structured: a[i] = structured[k / n]; b[i] = structured[k % n]; break;
        case Source::Random: random_pair(seed, j.op, k, &a[i], &b[i]); break;
        case Source::SigSweep: a[i] = 0x3F0000 | Bits(k >> 16); b[i] = 0x3F0000 | Bits(k & 0xFFFF); break;
        case Source::AllPairs: a[i] = Bits(k >> 24); b[i] = Bits(k) & 0xFFFFFF; break;
        case Source::File: a[i] = file[int(j.op)][k]->vector.a; b[i] = file[int(j.op)][k]->vector.b; break;
      }
    }
  }
};

// A range of one op's vectors from one source. The jobs (kChunk vectors
// each) are made from the segments as the threads take them, since an
// exhaustive-pairs run has 2^32 of them.
struct Segment {
  Op op;
  Source source;
  std::uint64_t first, count;
  std::uint64_t first_job;  // jobs of the segments before
};

struct Plan {
  std::vector<Segment> segments;
  std::uint64_t jobs = 0, vectors = 0;
  // By op: its vectors in the whole run, all shards together (the report's
  // "set_vectors": a merge checks its shards add up to it).
  std::vector<std::uint64_t> set_vectors = std::vector<std::uint64_t>(kOpCount);

  // Shard K/N of a set of `total` vectors: [total(K-1)/N, total K/N), so the
  // N shards cover it exactly once, and each shard gets its share of every
  // op and source (their costs differ a hundredfold).
  void add(const Options& o, Op op, Source source, std::uint64_t total) {
    set_vectors[int(op)] += total;
    const auto [first, end] = mc1::shard::shard_range(total, o.shard, o.shards);
    if (end == first) return;
    segments.push_back({op, source, first, end - first, jobs});
    jobs += (end - first + kChunk - 1) / kChunk;
    vectors += end - first;
  }

  Job job(std::uint64_t k) const {
    const auto later = std::upper_bound(segments.begin(), segments.end(), k,
                                        [](std::uint64_t n, const Segment& s) { return n < s.first_job; });
    const Segment& s = *(later - 1);
    const std::uint64_t first = s.first + (k - s.first_job) * kChunk;
    return {s.op, s.source, first, std::uint32_t(std::min<std::uint64_t>(kChunk, s.first + s.count - first))};
  }
};

Plan plan(const Options& o, const VectorSet& set) {
  Plan p;
  for (Op op : o.ops) {
    if (!o.vectors.empty()) p.add(o, op, Source::File, set.file[int(op)].size());
    else if (op == Op::Float) p.add(o, op, Source::Exhaustive, 1u << 16);
    else if (info(op).operands == 1) p.add(o, op, Source::Exhaustive, 1u << 24);
    else if (o.exhaustive_pairs) p.add(o, op, Source::AllPairs, std::uint64_t(1) << 48);
    else {
      if (o.structured) p.add(o, op, Source::Structured, std::uint64_t(set.structured.size()) * set.structured.size());
      p.add(o, op, Source::Random, o.random);
      if (o.long_run && op == Op::Mul) p.add(o, op, Source::SigSweep, std::uint64_t(1) << 32);
    }
  }
  return p;
}

// ---- results ---------------------------------------------------------------------

enum class Kind { RtlVsModel, ModelVsOracle, Unfaithful, NotCorrectlyRounded, ModelVsGolden };
const char* kind_name(Kind k) {
  static const char* const kNames[] = {"rtl-vs-model", "model-vs-oracle", "unfaithful", "not-correctly-rounded",
                                       "model-vs-golden"};
  return kNames[int(k)];
}

struct Failure {
  Kind kind;
  Issue vector;
  Result got;       // rtl (rtl-vs-model) or model (the others)
  Result expected;  // model (rtl-vs-model), oracle, or the golden file's
  double ulp;       // SIN/COS: model error in ulps; else NaN
  const Golden* line;  // --vectors: the file's line; else null
};

struct Stats {
  std::uint64_t vectors = 0;
  std::uint64_t set_vectors = 0;  // the op's vectors in the whole run (Plan::set_vectors)
  std::uint64_t rtl_vs_model = 0;
  std::uint64_t model_vs_oracle = 0;  // correctly rounded ops
  std::uint64_t not_cr = 0;           // SIN/COS
  std::uint64_t unfaithful = 0;       // SIN/COS: error >= 1 ulp or flags differ
  std::uint64_t golden = 0;           // --vectors: model != the file's expected result
  double max_ulp = 0;
  double cpu_seconds = 0;  // the CPU time its workers spent on it (thread_cpu_seconds)
  std::vector<Failure> failures;
  std::string rtl_error;  // a timing-contract violation, if any

  void merge(const Stats& s, unsigned show) {
    vectors += s.vectors;
    rtl_vs_model += s.rtl_vs_model;
    model_vs_oracle += s.model_vs_oracle;
    not_cr += s.not_cr;
    unfaithful += s.unfaithful;
    golden += s.golden;
    max_ulp = std::max(max_ulp, s.max_ulp);
    cpu_seconds += s.cpu_seconds;
    for (const Failure& f : s.failures)
      if (count(f.kind) < show) failures.push_back(f);
    if (rtl_error.empty()) rtl_error = s.rtl_error;
  }

  unsigned count(Kind k) const {
    return unsigned(std::count_if(failures.begin(), failures.end(), [k](const Failure& f) { return f.kind == k; }));
  }

  bool passed() const {
    return rtl_vs_model == 0 && model_vs_oracle == 0 && unfaithful == 0 && golden == 0 && rtl_error.empty();
  }
};

bool is_trig(Op op) { return op == Op::Sin || op == Op::Cos; }

// ---- the work --------------------------------------------------------------------

// The CPU time the calling thread has used (CLOCK_THREAD_CPUTIME_ID): a
// job's share of the machine, not the wall time it took while the thread
// waited for a core (with more threads than cores, or a loaded host, wall
// time counts the waits of every thread over again).
double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + double(t.tv_nsec) * 1e-9;
}

// One thread's engines and buffers; it runs whole jobs.
class Worker {
 public:
  Worker(const Options& o, const VectorSet& set) : o_(o), set_(set), a_(kChunk), b_(kChunk), m_(kChunk), r_(kChunk) {}

  Stats run(const Job& j) {
    const double start = thread_cpu_seconds();
    Stats s;
    s.vectors = j.count;
    set_.fill(j, a_.data(), b_.data());
    for (std::uint32_t i = 0; i < j.count; ++i) m_[i] = execute(j.op, a_[i], b_[i]);
    if (o_.rtl) check_rtl(j, &s);
    if (o_.oracle) check_oracle(j, &s);
    if (j.source == Source::File) check_golden(j, &s);
    s.cpu_seconds = thread_cpu_seconds() - start;
    return s;
  }

 private:
  void note(Stats* s, Kind kind, const Job& j, std::uint32_t i, Result got, Result expected, double ulp) {
    const Golden* line = j.source == Source::File ? set_.file[int(j.op)][j.first + i] : nullptr;
    if (s->count(kind) < o_.show) s->failures.push_back({kind, {j.op, a_[i], b_[i]}, got, expected, ulp, line});
  }

  void check_golden(const Job& j, Stats* s) {
    for (std::uint32_t i = 0; i < j.count; ++i) {
      const Golden& g = *set_.file[int(j.op)][j.first + i];
      if (!g.has_expected || m_[i] == g.expected) continue;
      ++s->golden;
      note(s, Kind::ModelVsGolden, j, i, m_[i], g.expected, NAN);
    }
  }

  void check_rtl(const Job& j, Stats* s) {
    const int u = int(info(j.op).unit);
    if (!rtl_[u]) rtl_[u] = std::make_unique<RtlUnit>(info(j.op).unit);
    try {
      rtl_[u]->run(j.op, a_.data(), b_.data(), r_.data(), j.count);
    } catch (const TimingError& e) {
      // None of this job's RTL results can be trusted: all count as mismatches.
      s->rtl_error = e.what();
      s->rtl_vs_model += j.count;
      rtl_[u].reset();  // its pipeline state is unknown now
      return;
    }
    for (std::uint32_t i = 0; i < j.count; ++i) {
      if (r_[i] == m_[i]) continue;
      ++s->rtl_vs_model;
      note(s, Kind::RtlVsModel, j, i, r_[i], m_[i], NAN);
    }
  }

  void check_oracle(const Job& j, Stats* s) {
    for (std::uint32_t i = 0; i < j.count; ++i) {
      if (is_trig(j.op)) {
        check_trig(j, i, s);
        continue;
      }
      const Result want = oracle_.run(j.op, a_[i], b_[i]);
      if (m_[i] == want) continue;
      ++s->model_vs_oracle;
      note(s, Kind::ModelVsOracle, j, i, m_[i], want, NAN);
    }
  }

  void check_trig(const Job& j, std::uint32_t i, Stats* s) {
    const Oracle::Measured m = oracle_.measure(j.op, a_[i], m_[i].value);
    s->max_ulp = std::max(s->max_ulp, m.ulp_error);
    if (m_[i] == m.rounded) return;
    if (m_[i].value != m.rounded.value) {
      ++s->not_cr;
      note(s, Kind::NotCorrectlyRounded, j, i, m_[i], m.rounded, m.ulp_error);
    }
    if (m.ulp_error >= 1.0 || m_[i].flags != m.rounded.flags) {
      ++s->unfaithful;
      note(s, Kind::Unfaithful, j, i, m_[i], m.rounded, m.ulp_error);
    }
  }

  const Options& o_;
  const VectorSet& set_;
  Oracle oracle_;
  std::unique_ptr<RtlUnit> rtl_[3];
  std::vector<Bits> a_, b_;
  std::vector<Result> m_, r_;
};

struct Run {
  std::vector<Stats> per_op = std::vector<Stats>(kOpCount);
  double wall_seconds = 0;
};

void show_progress(std::uint64_t done, std::uint64_t total, double seconds) {
  const double fraction = total ? double(done) / double(total) : 1.0;
  std::fprintf(stderr, "\rfp24-regress: %5.1f%%  %llu / %llu vectors  %s   ", 100.0 * fraction,
               (unsigned long long)done, (unsigned long long)total, cli::progress_times(seconds, fraction).c_str());
  std::fflush(stderr);
}

Run run_all(const Options& o) {
  VectorSet set;
  set.seed = o.seed;
  for (const Golden& g : o.user) set.file[int(g.vector.op)].push_back(&g);
  const Plan jobs = plan(o, set);
  const std::uint64_t total = jobs.vectors;

  Run run;
  for (int op = 0; op < kOpCount; ++op) run.per_op[op].set_vectors = jobs.set_vectors[op];
  std::mutex merge;
  std::condition_variable finished;  // the last worker is done: the wall time ends there
  std::atomic<std::uint64_t> next{0};
  std::atomic<std::uint64_t> done{0};
  unsigned running = o.threads;  // under `merge`
  std::exception_ptr failed;      // a worker's first error (under `merge`), thrown once all have ended
  auto work = [&] {
    try {
      Worker w(o, set);
      for (std::uint64_t k; (k = next.fetch_add(1)) < jobs.jobs;) {
        const Job job = jobs.job(k);
        const Stats s = w.run(job);
        std::lock_guard<std::mutex> lock(merge);
        run.per_op[int(job.op)].merge(s, o.show);
        done += job.count;
      }
    } catch (...) {  // out of a thread's function it would end the program
      next = jobs.jobs;  // the others take no more jobs
      std::lock_guard<std::mutex> lock(merge);
      if (!failed) failed = std::current_exception();
    }
    std::lock_guard<std::mutex> lock(merge);
    if (--running == 0) finished.notify_all();
  };
  const auto start = Clock::now();
  std::vector<std::thread> threads;
  try {
    for (unsigned t = 0; t < o.threads; ++t) threads.emplace_back(work);
  } catch (const std::system_error& e) {
    next = jobs.jobs;  // the threads started take no more jobs and end
    for (std::thread& t : threads) t.join();
    throw std::runtime_error("--threads " + std::to_string(o.threads) + ": the host started " +
                             std::to_string(threads.size()) + " threads and no more (" + e.what() + ")");
  }
  const bool tty = isatty(STDERR_FILENO) != 0;
  std::unique_lock<std::mutex> lock(merge);
  while (!finished.wait_for(lock, std::chrono::milliseconds(500), [&] { return running == 0; })) {
    lock.unlock();
    if (tty) show_progress(done, total, std::chrono::duration<double>(Clock::now() - start).count());
    lock.lock();
  }
  lock.unlock();
  for (std::thread& t : threads) t.join();
  if (tty) std::fputs("\n", stderr);
  if (failed) std::rethrow_exception(failed);
  run.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return run;
}

// ---- reports ---------------------------------------------------------------------

bool passed(const Options& o, const Run& run) {
  for (Op op : o.ops)
    if (!run.per_op[int(op)].passed()) return false;
  return true;
}

std::string count_or_dash(bool applies, std::uint64_t n) { return applies ? std::to_string(n) : "-"; }

std::string failure_line(const Options& o, const Failure& f) {
  const char* got = f.kind == Kind::RtlVsModel ? "rtl" : "model";
  const char* want = f.kind == Kind::RtlVsModel ? "model" : "oracle";
  if (f.line) {  // a file's line, located and decoded as fp24-run --check prints it; "expected" is
                 // the golden value, the model's (rtl-vs-model) or the oracle's
    const Golden g{f.vector, f.expected, f.line->line, true};
    return "  " + std::string(kind_name(f.kind)) + ": " + mismatch_line(o.vectors, g, got, f.got) + "\n";
  }
  std::string line = "  " + std::string(kind_name(f.kind)) + ": " + format_vector(f.vector) + " -> " +
                     format_result(f.got) + " (" + got + ") / " + format_result(f.expected) + " (" + want + ")";
  if (!std::isnan(f.ulp)) {
    char buf[32];
    std::snprintf(buf, sizeof buf, ", %.4f ulp", f.ulp);
    line += buf;
  }
  return line + "\n";
}

std::string text_report(const Options& o, const Run& run) {
  std::ostringstream t;
  char buf[256];
  if (o.vectors.empty())
    t << "fp24-regress: seed " << o.seed << ", "
      << (o.exhaustive_pairs ? "all 2^48 pairs" : std::to_string(o.random) + " random pairs")
      << " per two-operand op" << (o.structured || o.exhaustive_pairs ? "" : ", no structured set")
      << (o.long_run ? ", long sweep" : "");
  else
    t << "fp24-regress: " << o.vectors << ", " << o.user.size() << " vectors";
  t << ", engines model" << (o.rtl ? " rtl" : "") << (o.oracle ? " oracle" : "")
    << ", " << o.threads << " threads";
  if (o.shards > 1) t << ", shard " << o.shard << "/" << o.shards;
  t << "\n";
  std::snprintf(buf, sizeof buf, "%-6s %12s %12s %15s %10s %11s %9s %9s %13s\n", "op", "vectors", "rtl!=model",
                "model!=oracle", "not-CR", "unfaithful", "max-ulp", "cpu-s", "model!=golden");
  t << buf;
  for (Op op : o.ops) {
    const Stats& s = run.per_op[int(op)];
    const bool trig = is_trig(op) && o.oracle;
    char ulp[16] = "-";
    if (trig) std::snprintf(ulp, sizeof ulp, "%.4f", s.max_ulp);
    std::snprintf(buf, sizeof buf, "%-6s %12llu %12s %15s %10s %11s %9s %9.1f %13s\n", info(op).name.data(),
                  (unsigned long long)s.vectors, count_or_dash(o.rtl, s.rtl_vs_model).c_str(),
                  count_or_dash(o.oracle && !is_trig(op), s.model_vs_oracle).c_str(),
                  count_or_dash(trig, s.not_cr).c_str(), count_or_dash(trig, s.unfaithful).c_str(), ulp,
                  s.cpu_seconds, count_or_dash(!o.vectors.empty(), s.golden).c_str());
    t << buf;
  }
  for (Op op : o.ops) {
    const Stats& s = run.per_op[int(op)];
    if (!s.rtl_error.empty()) t << info(op).name << ": RTL timing: " << s.rtl_error << "\n";
    if (s.failures.empty()) continue;
    t << info(op).name << ": first differing vectors (replay: echo '<vector>' | fp24-run --engine rtl|model|oracle)\n";
    for (const Failure& f : s.failures) t << failure_line(o, f);
  }
  std::snprintf(buf, sizeof buf, "wall time %.1f s\n", run.wall_seconds);
  t << buf << (passed(o, run) ? "PASS" : "FAIL") << "\n";
  return t.str();
}

using mc1::json::quote;  // the project's one JSON string escaper

std::string json_number(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string json_failure(const Failure& f) {
  return "{\"kind\": " + quote(kind_name(f.kind)) + ", \"vector\": " + quote(format_vector(f.vector)) +
         ", \"got\": " + quote(format_result(f.got)) + ", \"expected\": " +
         quote(format_result(f.expected)) + ", \"ulp_error\": " + json_number(f.ulp) +
         ", \"line\": " + (f.line ? std::to_string(f.line->line) : std::string("null")) + "}";
}

std::string json_op(const Options& o, Op op, const Stats& s) {
  const bool trig = is_trig(op) && o.oracle;
  auto opt = [](bool applies, std::uint64_t n) { return applies ? std::to_string(n) : std::string("null"); };
  std::string j = "    {\"op\": " + quote(std::string(info(op).name)) +
                  ", \"vectors\": " + std::to_string(s.vectors) +
                  ", \"set_vectors\": " + std::to_string(s.set_vectors) +
                  ", \"rtl_vs_model\": " + opt(o.rtl, s.rtl_vs_model) +
                  ", \"model_vs_oracle\": " + opt(o.oracle && !is_trig(op), s.model_vs_oracle) +
                  ", \"not_correctly_rounded\": " + opt(trig, s.not_cr) +
                  ", \"unfaithful\": " + opt(trig, s.unfaithful) +
                  ", \"model_vs_golden\": " + opt(!o.vectors.empty(), s.golden) +
                  ", \"max_ulp_error\": " + (trig ? json_number(s.max_ulp) : "null") +
                  ", \"cpu_seconds\": " + json_number(s.cpu_seconds) +
                  ", \"rtl_timing_error\": " + (s.rtl_error.empty() ? "null" : quote(s.rtl_error)) +
                  ", \"passed\": " + (s.passed() ? "true" : "false") + ", \"failures\": [";
  for (std::size_t i = 0; i < s.failures.size(); ++i) j += (i ? ", " : "") + json_failure(s.failures[i]);
  return j + "]}";
}

std::string json_report(const Options& o, const Run& run) {
  std::string j = "{\n  \"schema\": \"fp24-regress/1\",\n  \"program\": \"fp24-regress\",\n  \"vectors_file\": " +
                  (o.vectors.empty() ? std::string("null") : quote(o.vectors)) +
                  ",\n  \"seed\": " + std::to_string(o.seed) +
                  ",\n  \"random_pairs\": " + std::to_string(o.random) +
                  ",\n  \"long\": " + (o.long_run ? "true" : "false") +
                  ",\n  \"structured\": " + (o.structured ? "true" : "false") +
                  ",\n  \"exhaustive_pairs\": " + (o.exhaustive_pairs ? "true" : "false") +
                  ",\n  \"shard\": " + quote(std::to_string(o.shard) + "/" + std::to_string(o.shards)) +
                  ",\n  \"engines\": [\"model\"" + (o.rtl ? ", \"rtl\"" : "") + (o.oracle ? ", \"oracle\"" : "") +
                  "],\n  \"threads\": " + std::to_string(o.threads) +
                  ",\n  \"wall_seconds\": " + json_number(run.wall_seconds) +
                  ",\n  \"passed\": " + (passed(o, run) ? "true" : "false") + ",\n  \"ops\": [\n";
  for (std::size_t i = 0; i < o.ops.size(); ++i)
    j += json_op(o, o.ops[i], run.per_op[int(o.ops[i])]) + (i + 1 < o.ops.size() ? ",\n" : "\n");
  return j + "  ]\n}\n";
}

// --merge: what the merge takes on trust from each shard checked first
// (shard::check_items), then the merge (fp24_regress_merge.cpp).
int merge(const CLI::App& app, const Options& o) {
  for (const CLI::Option* other : app.get_options())  // a merge runs nothing: only --json and --text apply
    if (other->count() && !other->check_name("--merge") && !other->check_name("--json") && !other->check_name("--text"))
      return cli::usage_error(app, "--merge excludes " + other->get_name() + ": a merge runs nothing");
  const mc1::shard::ItemRules ops{
      "ops", "op", [](const std::string& name) { return op_from_name(name).has_value(); },
      {"vectors", "rtl_vs_model", "model_vs_oracle", "not_correctly_rounded", "unfaithful", "model_vs_golden"},
      {"rtl_vs_model", "model_vs_oracle", "unfaithful", "model_vs_golden"},  // as Stats::passed
      "rtl_timing_error"};
  try {
    std::vector<mc1::shard::Report> reports;
    for (const std::string& f : o.merge) reports.push_back(mc1::shard::read_report(f, "fp24-regress/1"));
    mc1::shard::check_items(reports, ops);
  } catch (const mc1::json::JsonError& e) {
    std::fprintf(stderr, "fp24-regress: --merge: %s\n", e.what());
    return cli::kExitUsage;
  } catch (const cli::UsageError& e) {
    return cli::usage_error(app, std::string("--merge: ") + e.what());
  }
  return merge_reports(app, o.merge, o.json, o.text);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{kDescription, "fp24-regress"};
  cli::conventions(app,
                  "Exit status: 0 all match; 1 a mismatch, or a report that could not be written\n"
                  "(what was at its path is left as it was); 2 usage or input error (a report\n"
                  "path that cannot be written is one, found before the run).");
  Options o;
  std::string ops, shard;
  cli::Files files;
  add_options(app, o, ops, shard, files);
  add_exclusions(app);
  if (auto rc = cli::parse(app, argc, argv)) return *rc;
  try {
    files.check();  // no report on an input or the other report; each writable before the run
  } catch (const cli::UsageError& e) {
    return cli::usage_error(app, e.what());
  }
  if (!o.merge.empty()) return cli::flush_stdout("fp24-regress", merge(app, o));
  try {
    o.ops = app.count("--ops") ? parse_ops(ops) : all_ops();
    if (!shard.empty()) parse_shard(shard, o);
    if (!o.vectors.empty()) read_user_vectors(o, app.count("--ops") != 0);
  } catch (const VectorError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return cli::kExitUsage;
  } catch (const cli::UsageError& e) {
    return cli::usage_error(app, e.what());
  }
  if (o.long_run) o.random = std::max(o.random, kLongRandom);
  Run run;
  try {
    run = run_all(o);
  } catch (const std::exception& e) {  // a thread the host would not start, a worker's error
    std::fprintf(stderr, "fp24-regress: %s\n", e.what());
    return cli::kExitFailed;
  }
  const std::string text = text_report(o, run);
  std::fputs(text.c_str(), stdout);
  const bool written = mc1::shard::write_texts({{o.text, text}, {o.json, json_report(o, run)}}, "fp24-regress");
  return cli::flush_stdout("fp24-regress", passed(o, run) && written ? cli::kExitOk : cli::kExitFailed);
}
