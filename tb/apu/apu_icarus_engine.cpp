// IcarusEngine: apu_core under Icarus Verilog, a vvp child process driven
// over pipes (apu_icarus_engine.hpp; the bench and its commands:
// tb/apu/apu_icarus_lockstep_tb.sv).
#include "apu_icarus_engine.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <mutex>
#include <utility>

extern char** environ;

#ifndef MC1_ICARUS_VVP_FILE
#define MC1_ICARUS_VVP_FILE ""
#endif
#ifndef MC1_VVP_PROGRAM
#define MC1_VVP_PROGRAM "vvp"
#endif

namespace mc1::apu {

namespace {

constexpr int kFCompletionPorts = 5;  // mul, add, func RECIP/SQRT, func SIN/COS, LD (as RtlEngine)
constexpr int kFCommitPorts = 6;      // the completions; MOVAF/LIF of t - 1
constexpr int kReplyTimeoutMs = 300'000;  // a bench that answers nothing in 5 minutes hangs
constexpr std::size_t kPoolMax = 4;      // idle benches kept for the next engine

std::string hex(std::uint64_t v, int digits) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "0x%0*llx", digits, static_cast<unsigned long long>(v));
  return buf;
}

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;  // x, X, z, Z: unknown bits
}

// The status after an edge (the bench's STATUS fields).
struct Status {
  RunState run = RunState::Idle;
  Fault fault = Fault::None;
  bool program_ready = false, data_ready = false;
  std::uint8_t psel = 0, dsel = 0, cc = 0, flags = 0;
  // The coming cycle's F completions (freg()'s bypass).
  std::uint8_t fc_en = 0;
  std::array<std::uint8_t, kFCommitPorts> fc_idx{};
  std::array<std::uint32_t, kFCommitPorts> fc_val{};
  bool unit_mismatch = false;
};

// ---- the child process --------------------------------------------------------

// The vvp child and its pipes.
class Process {
 public:
  Process(std::string vvp, std::string file);
  ~Process();

  const std::string& vvp() const { return vvp_; }
  const std::string& file() const { return file_; }
  bool healthy() const { return healthy_; }

  // Queues a command (no answer).
  void send(const std::string& cmd) { out_ += cmd, out_ += '\n'; }
  // Sends the queue and `cmd`, returns the reply line (its tag and a space
  // stripped). Lines of the simulation's own output before it that say
  // ERROR or ASSERT are kept in errors(): the caller fails with them.
  std::string request(const std::string& cmd, const std::string& where);
  const std::string& errors() const { return errors_; }
  void fail() { healthy_ = false; }
  // The bench's last lines (a failure's context).
  std::string tail() const;

 private:
  void flush(const std::string& where);
  bool read_line(std::string& line, const std::string& where);  // false at the end of the output
  [[noreturn]] void died(const std::string& where);

  std::string vvp_, file_;
  pid_t pid_ = -1;
  int to_child_ = -1, from_child_ = -1;
  std::string out_, in_;
  std::deque<std::string> last_;  // the last lines that were not replies
  std::string errors_;            // ERROR / ASSERT lines not yet failed with
  bool healthy_ = true;
};

Process::Process(std::string vvp, std::string file) : vvp_(std::move(vvp)), file_(std::move(file)) {
  struct stat st {};
  if (file_.empty())
    throw IcarusError("icarus engine: no vvp file (the build found no iverilog; give one with --icarus-vvp FILE or "
                      "MC1_ICARUS_VVP)");
  if (::stat(file_.c_str(), &st) != 0 || !S_ISREG(st.st_mode))
    throw IcarusError("icarus engine: vvp file '" + file_ + "' not found (build it: cmake --build BUILD --target "
                      "apu_icarus_vvp; or name another with --icarus-vvp FILE / MC1_ICARUS_VVP)");
  int in[2], out[2];
  if (::pipe2(in, O_CLOEXEC) != 0) throw IcarusError(std::string("icarus engine: pipe: ") + std::strerror(errno));
  if (::pipe2(out, O_CLOEXEC) != 0) {
    ::close(in[0]), ::close(in[1]);
    throw IcarusError(std::string("icarus engine: pipe: ") + std::strerror(errno));
  }
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_adddup2(&fa, in[0], 0);
  posix_spawn_file_actions_adddup2(&fa, out[1], 1);
  posix_spawn_file_actions_adddup2(&fa, out[1], 2);
  std::vector<std::string> args = {vvp_, "-n", file_};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const int rc = ::posix_spawnp(&pid_, vvp_.c_str(), &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  ::close(in[0]);
  ::close(out[1]);
  to_child_ = in[1];
  from_child_ = out[0];
  if (rc != 0) {
    ::close(to_child_), ::close(from_child_);
    throw IcarusError("icarus engine: cannot run '" + vvp_ + "': " + std::strerror(rc) +
                      " (Icarus Verilog's vvp; tools/setup.sh installs iverilog)");
  }
  // The bench says "ready" once reset.
  std::string line;
  const std::string where = "at its start";
  while (read_line(line, where)) {
    if (line == "ready") return;
    last_.push_back(line);
  }
  died(where);
}

Process::~Process() {
  if (pid_ > 0) {
    if (healthy_) {
      out_ = "x\n";
      try {
        flush("exit");
      } catch (const IcarusError&) {
      }
    }
    ::close(to_child_);
    ::close(from_child_);
    int status = 0;
    // The bench ends on "x" or at the end of its input; a hung one is killed.
    for (int i = 0; i < 200 && ::waitpid(pid_, &status, WNOHANG) == 0; ++i) ::usleep(10'000);
    if (::waitpid(pid_, &status, WNOHANG) == 0) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, &status, 0);
    }
  }
}

// Writes the queue; a bench that has ended fails it (EPIPE: SIGPIPE is
// blocked on this thread meanwhile, and a pending one taken, so the program
// is not killed).
void Process::flush(const std::string& where) {
  if (out_.empty()) return;
  sigset_t pipe_set, old;
  sigemptyset(&pipe_set);
  sigaddset(&pipe_set, SIGPIPE);
  pthread_sigmask(SIG_BLOCK, &pipe_set, &old);
  std::size_t done = 0;
  int err = 0;
  while (done < out_.size()) {
    const ssize_t w = ::write(to_child_, out_.data() + done, out_.size() - done);
    if (w < 0) {
      if (errno == EINTR) continue;
      err = errno;
      break;
    }
    done += static_cast<std::size_t>(w);
  }
  if (err == EPIPE) {
    const timespec zero{0, 0};
    while (sigtimedwait(&pipe_set, nullptr, &zero) == SIGPIPE) {
    }
  }
  pthread_sigmask(SIG_SETMASK, &old, nullptr);
  out_.clear();
  if (err) died(where);
}

bool Process::read_line(std::string& line, const std::string& where) {
  for (;;) {
    const auto nl = in_.find('\n');
    if (nl != std::string::npos) {
      line.assign(in_, 0, nl);
      in_.erase(0, nl + 1);
      return true;
    }
    pollfd pfd{from_child_, POLLIN, 0};
    const int r = ::poll(&pfd, 1, kReplyTimeoutMs);
    if (r < 0 && errno == EINTR) continue;
    if (r == 0) {
      healthy_ = false;
      throw IcarusError("icarus engine: the bench (" + file_ + ") did not answer for " +
                        std::to_string(kReplyTimeoutMs / 1000) + " s, " + where + tail());
    }
    char buf[65536];
    const ssize_t n = ::read(from_child_, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      if (!in_.empty()) {
        line.swap(in_);
        in_.clear();
        return true;
      }
      return false;
    }
    in_.append(buf, static_cast<std::size_t>(n));
  }
}

std::string Process::tail() const {
  if (last_.empty()) return "";
  std::string s = "; its last output:";
  for (const auto& l : last_) s += "\n    " + l;
  return s;
}

void Process::died(const std::string& where) {
  healthy_ = false;
  std::string line;
  try {
    while (read_line(line, where)) {
      last_.push_back(line);
      if (last_.size() > 12) last_.pop_front();
    }
  } catch (const IcarusError&) {
  }
  ::close(to_child_);
  ::close(from_child_);
  int status = 0;
  ::waitpid(pid_, &status, 0);
  pid_ = -1;
  std::string how = WIFEXITED(status)     ? "exited with status " + std::to_string(WEXITSTATUS(status))
                    : WIFSIGNALED(status) ? "was killed by signal " + std::to_string(WTERMSIG(status))
                                          : "ended";
  throw IcarusError("icarus engine: vvp " + file_ + " " + how + " " + where + tail());
}

std::string Process::request(const std::string& cmd, const std::string& where) {
  if (!healthy_) throw IcarusError("icarus engine: the bench failed before, " + where);
  send(cmd);
  flush(where);
  const char tag = cmd[0] == 'u' ? 'r' : cmd[0];
  std::string line;
  bool in_error = false;
  while (read_line(line, where)) {
    if (!line.empty() && line[0] == tag && (line.size() == 1 || line[1] == ' '))
      return line.size() > 2 ? line.substr(2) : std::string();
    // The simulation's own output: an assertion ($error: "ERROR: file:line:
    // ... ASSERT name", then indented "Time: ... Scope: ..." lines) is kept
    // for the caller to fail with; anything else only as context.
    if (line.rfind("ERROR", 0) == 0 || line.rfind("FATAL", 0) == 0 || line.find("ASSERT") != std::string::npos) {
      errors_ += "    " + line + "\n";
      in_error = true;
    } else if (in_error && !line.empty() && (line[0] == ' ' || line[0] == '\t')) {
      errors_ += "    " + line + "\n";
    } else {
      in_error = false;
    }
    last_.push_back(line);
    if (last_.size() > 12) last_.pop_front();
  }
  if (!errors_.empty()) {
    healthy_ = false;
    throw IcarusError("icarus engine: the simulation reports an error and ends " + where + ":\n" + errors_);
  }
  died(where);
}

// ---- idle benches for the next engine -------------------------------------------

// Engines come and go (apu-cosim makes two for each random case), and a vvp
// start costs as much as a few hundred cycles: a bench whose engine ends
// healthy is reset ("z": memories cleared, the core reset, as at its start)
// and kept for the next engine on the same vvp file.
class Pool {
 public:
  static Pool& get() {
    static Pool pool;
    return pool;
  }
  std::unique_ptr<Process> take(const std::string& vvp, const std::string& file) {
    std::lock_guard<std::mutex> lock(m_);
    for (auto it = idle_.begin(); it != idle_.end(); ++it) {
      if ((*it)->vvp() == vvp && (*it)->file() == file) {
        auto p = std::move(*it);
        idle_.erase(it);
        return p;
      }
    }
    return nullptr;
  }
  void give(std::unique_ptr<Process> p) {
    std::lock_guard<std::mutex> lock(m_);
    if (idle_.size() < kPoolMax) idle_.push_back(std::move(p));
  }

 private:
  std::mutex m_;
  std::vector<std::unique_ptr<Process>> idle_;
};

// A reply's fields: whitespace-separated tokens, each a number in hex or
// binary as the bench printed it at its width, 'x'/'z' digits for unknown
// bits.
class Fields {
 public:
  Fields(const std::string& line, std::size_t count, const char* what) {
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && line[i] == ' ') ++i;
      const std::size_t j = line.find(' ', i);
      const std::size_t end = j == std::string::npos ? line.size() : j;
      if (end > i) tokens_.push_back(line.substr(i, end - i));
      i = end;
    }
    if (tokens_.size() < count)
      throw IcarusError(std::string("icarus engine: a malformed reply to '") + what + "': '" + line + "'");
  }
  // Bits [pos, pos + width) of token t (radix 16 or 2); nullopt if any is unknown.
  bool get(std::size_t t, int radix, int pos, int width, std::uint32_t& out) const {
    const std::string& s = tokens_.at(t);
    const int per = radix == 16 ? 4 : 1;
    std::uint64_t v = 0;
    for (int b = pos + width - 1; b >= pos; --b) {
      const int digit_from_right = b / per;
      if (digit_from_right >= static_cast<int>(s.size())) {
        v <<= 1;  // beyond the printed width: 0
        continue;
      }
      const int d = hex_digit(s[s.size() - 1 - static_cast<std::size_t>(digit_from_right)]);
      if (d < 0 || d >= radix) return false;
      v = v << 1 | static_cast<std::uint64_t>((d >> (b % per)) & 1);
    }
    out = static_cast<std::uint32_t>(v);
    return true;
  }
  std::size_t size() const { return tokens_.size(); }
  const std::string& token(std::size_t t) const { return tokens_.at(t); }

 private:
  std::vector<std::string> tokens_;
};

}  // namespace

// ---- the engine -------------------------------------------------------------------

class IcarusEngine::Impl {
 public:
  explicit Impl(const Options& o);
  ~Impl();

  std::unique_ptr<Process> p;
  std::uint64_t cycle = 0;
  std::uint16_t last_pc = 0;  // the last record's
  std::uint8_t last_psel = 0;
  Status status;
  bool status_valid = false;  // an MPU call since the last reply changed inputs
  std::vector<std::uint32_t> bank;  // the MPU's data bank, as last fetched
  bool bank_valid = false;
  std::array<std::uint32_t, kNumFRegs> f{};
  std::array<std::uint16_t, kNumARegs> a{};
  bool regs_valid = false;
  ApuCounters counters;

  // "at cycle N (pc P)": the place of a call between cycles.
  std::string where() const {
    return "at cycle " + std::to_string(cycle) + " (last pc " + hex(last_pc, 3) + ")";
  }
  // A request; the simulation's ERROR/ASSERT lines fail it, in cycle
  // `in_cycle` (pc, psel) or between cycles.
  std::string request(const std::string& cmd, const std::string& where_text) {
    std::string reply = p->request(cmd, where_text);
    check_errors(where_text);
    return reply;
  }
  void check_errors(const std::string& where_text) {
    if (!p->errors().empty()) {
      p->fail();
      std::string lines = p->errors();
      if (!lines.empty() && lines.back() == '\n') lines.pop_back();
      throw IcarusError("icarus engine: the simulation reports an error " + where_text + ":\n" + lines, cycle,
                        last_pc, last_psel);
    }
  }
  [[noreturn]] void x_on(const std::string& what, const std::string& where_text) {
    p->fail();
    throw IcarusError("icarus engine: X on " + what + " " + where_text, cycle, last_pc, last_psel);
  }
  std::uint32_t need(const Fields& fl, std::size_t t, int radix, int pos, int width, const std::string& what,
                     const std::string& where_text) {
    std::uint32_t v = 0;
    if (!fl.get(t, radix, pos, width, v)) x_on(what, where_text);
    return v;
  }
  // STATUS from token t on.
  void parse_status(const Fields& fl, std::size_t t, const std::string& where_text);
  void ensure_status() {
    if (status_valid) return;
    const std::string w = where();
    const std::string reply = request("q", w);
    parse_status(Fields(reply, 12, "q"), 0, w);
  }
  // Both register files, as the bench reads them after the last edge.
  void ensure_regs() {
    if (regs_valid) return;
    const std::string w = where();
    const std::string reply = request("f", w);
    if (reply.size() != static_cast<std::size_t>(kNumFRegs * 6 + kNumARegs * 4))
      throw IcarusError("icarus engine: a malformed reply to 'f' (" + std::to_string(reply.size()) + " characters)");
    std::size_t pos = 0;
    auto take = [&](int digits, const std::string& what) {
      std::uint32_t v = 0;
      for (int d = 0; d < digits; ++d) {
        const int h = hex_digit(reply[pos++]);
        if (h < 0) x_on(what, w);
        v = v << 4 | static_cast<std::uint32_t>(h);
      }
      return v;
    };
    for (int r = 0; r < kNumFRegs; ++r) f[static_cast<std::size_t>(r)] = take(6, "F" + std::to_string(r));
    for (int r = 0; r < kNumARegs; ++r)
      a[static_cast<std::size_t>(r)] = static_cast<std::uint16_t>(take(4, "A" + std::to_string(r)));
    regs_valid = true;
  }
  void clocked() {
    bank_valid = false;
    regs_valid = false;
  }
};

IcarusEngine::Impl::Impl(const Options& o) {
  const std::string vvp = o.vvp.empty() ? std::string(MC1_VVP_PROGRAM) : o.vvp;
  const std::string file = o.vvp_file.empty() ? IcarusEngine::default_vvp_file() : o.vvp_file;
  p = Pool::get().take(vvp, file);
  if (!p) p = std::make_unique<Process>(vvp, file);
}

// MC1_ICARUS_FRESH=1: no bench is kept, every engine starts its own from
// the power-on state (flip-flops without a reset X), at ~0.1 s an engine.
IcarusEngine::Impl::~Impl() {
  const char* fresh = std::getenv("MC1_ICARUS_FRESH");
  if (p && p->healthy() && !(fresh && *fresh && std::strcmp(fresh, "0") != 0)) {
    p->send("z");
    Pool::get().give(std::move(p));
  }
}

void IcarusEngine::Impl::parse_status(const Fields& fl, std::size_t t, const std::string& w) {
  Status& s = status;
  s.run = static_cast<RunState>(need(fl, t + 0, 16, 0, 2, "apu2mpu_run_state", w));
  s.fault = static_cast<Fault>(need(fl, t + 1, 16, 0, 3, "apu2mpu_fault", w));
  s.program_ready = need(fl, t + 2, 16, 0, 1, "apu2mpu_program_ready", w);
  s.data_ready = need(fl, t + 3, 16, 0, 1, "apu2mpu_data_ready", w);
  s.psel = static_cast<std::uint8_t>(need(fl, t + 4, 16, 0, 1, "apu2mpu_psel", w));
  s.dsel = static_cast<std::uint8_t>(need(fl, t + 5, 16, 0, 1, "apu2mpu_dsel", w));
  s.cc = static_cast<std::uint8_t>(need(fl, t + 6, 16, 0, 4, "apu2mpu_cc", w));
  s.flags = static_cast<std::uint8_t>(need(fl, t + 7, 16, 0, 5, "apu2mpu_flags", w));
  s.fc_en = static_cast<std::uint8_t>(need(fl, t + 8, 2, 0, kFCommitPorts, "dbg_fc_en", w));
  for (int port = 0; port < kFCommitPorts; ++port) {
    if (!((s.fc_en >> port) & 1)) continue;
    const std::string which = " (port " + std::to_string(port) + ")";
    s.fc_idx[port] = static_cast<std::uint8_t>(need(fl, t + 9, 2, 6 * port, 6, "dbg_fc_idx" + which, w));
    s.fc_val[port] = need(fl, t + 10, 16, 24 * port, 24, "dbg_fc_val" + which, w);
  }
  s.unit_mismatch = need(fl, t + 11, 16, 0, 1, "dbg_unit_mismatch", w);
  status_valid = true;
  // Sticky in the core: set by the first cycle in which a unit's result
  // valid and the interlock's tag pipe disagree (a netlist has no
  // assertions, but has this port).
  if (s.unit_mismatch) {
    p->fail();
    throw IcarusError("icarus engine: dbg_unit_mismatch " + w +
                          ": a unit's result came out of step with the interlock's tags",
                      cycle, last_pc, last_psel);
  }
}

std::string IcarusEngine::default_vvp_file() {
  if (const char* env = std::getenv("MC1_ICARUS_VVP"); env && *env) return env;
  return MC1_ICARUS_VVP_FILE;
}

IcarusEngine::IcarusEngine(const Options& o) : impl_(std::make_unique<Impl>(o)) {}
IcarusEngine::~IcarusEngine() = default;

const std::string& IcarusEngine::vvp_file() const { return impl_->p->file(); }

// ---- MPU side: queued, answered by the next request -------------------------------

void IcarusEngine::write_program(std::uint16_t addr, const Encoded& word) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "p %x %016llx%016llx", addr % kProgramWords,
                static_cast<unsigned long long>(word.hi), static_cast<unsigned long long>(word.lo));
  impl_->p->send(buf);
}

void IcarusEngine::write_data(std::uint16_t addr, std::uint32_t value) {
  addr %= kDataWords;
  value &= 0xFFFFFFu;
  char buf[32];
  std::snprintf(buf, sizeof buf, "d %x %x", addr, value);
  impl_->p->send(buf);
  if (impl_->bank_valid) impl_->bank[addr] = value;
}

void IcarusEngine::read_data_block(std::uint16_t addr, std::uint32_t* out, std::size_t n) const {
  Impl& m = *impl_;
  if (!m.bank_valid) {
    const std::string w = m.where();
    const std::string reply = m.request("b", w);
    if (reply.size() != static_cast<std::size_t>(kDataWords) * 6)
      throw IcarusError("icarus engine: a malformed reply to 'b' (" + std::to_string(reply.size()) + " characters)");
    m.bank.resize(kDataWords);
    for (int i = 0; i < kDataWords; ++i) {
      std::uint32_t v = 0;
      for (int d = 0; d < 6; ++d) {
        const int h = hex_digit(reply[static_cast<std::size_t>(i) * 6 + static_cast<std::size_t>(d)]);
        if (h < 0) m.x_on("the MPU's data bank word " + hex(static_cast<std::uint64_t>(i), 3), w);
        v = v << 4 | static_cast<std::uint32_t>(h);
      }
      m.bank[static_cast<std::size_t>(i)] = v;
    }
    m.bank_valid = true;
  }
  for (std::size_t i = 0; i < n; ++i) out[i] = m.bank[(addr + i) % kDataWords];
}

std::uint32_t IcarusEngine::read_data(std::uint16_t addr) const {
  std::uint32_t v = 0;
  read_data_block(addr, &v, 1);
  return v;
}

void IcarusEngine::hand_over_program() {
  impl_->p->send("h");
  impl_->status_valid = false;
}

void IcarusEngine::hand_over_data() {
  impl_->p->send("g");
  impl_->status_valid = false;
}

void IcarusEngine::start(std::uint16_t pc) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "a %x", pc % kProgramWords);
  impl_->p->send(buf);
  impl_->status_valid = false;
}

bool IcarusEngine::program_ready() const {
  impl_->ensure_status();
  return impl_->status.program_ready;
}

bool IcarusEngine::data_ready() const {
  impl_->ensure_status();
  return impl_->status.data_ready;
}

RunState IcarusEngine::state() const {
  impl_->ensure_status();
  return impl_->status.run;
}

Fault IcarusEngine::fault() const {
  impl_->ensure_status();
  return impl_->status.fault;
}

std::uint8_t IcarusEngine::flags() const {
  impl_->ensure_status();
  return impl_->status.flags;
}

std::uint8_t IcarusEngine::cc() const {
  impl_->ensure_status();
  return impl_->status.cc;
}

bool IcarusEngine::unit_mismatch() const {
  impl_->ensure_status();
  return impl_->status.unit_mismatch;
}

std::uint64_t IcarusEngine::cycle() const { return impl_->cycle; }

// ---- clocking -----------------------------------------------------------------------

// One round trip: the cycle's debug ports (before the edge), the edge, the
// state after it. Commits sorted as RtlEngine sorts them.
void IcarusEngine::step(CycleRecord& rec) {
  Impl& m = *impl_;
  const std::string w0 = "in cycle " + std::to_string(m.cycle);
  const std::string reply = m.p->request("s", w0);
  const Fields fl(reply, 31, "s");
  // The record's place first: an assertion of this cycle names it.
  std::uint32_t pc = 0, psel = 0;
  const bool pc_known = fl.get(0, 16, 0, 10, pc), psel_known = fl.get(4, 16, 0, 1, psel);
  if (pc_known) m.last_pc = static_cast<std::uint16_t>(pc);
  if (psel_known) m.last_psel = static_cast<std::uint8_t>(psel);
  const std::string w = "in cycle " + std::to_string(m.cycle) + ", pc " + hex(m.last_pc, 3);
  m.check_errors(w);
  rec.cycle = m.cycle;
  rec.pc = static_cast<std::uint16_t>(m.need(fl, 0, 16, 0, 10, "dbg_pc", w));
  rec.issued = m.need(fl, 1, 16, 0, 1, "dbg_issue", w);
  const std::uint32_t units = m.need(fl, 2, 16, 0, 3, "dbg_unit_issue", w);
  (void)units;
  rec.stall = static_cast<Stall>(m.need(fl, 3, 16, 0, 3, "dbg_stall_reason", w));
  rec.psel = static_cast<std::uint8_t>(m.need(fl, 4, 16, 0, 1, "apu2mpu_psel", w));
  rec.dsel = static_cast<std::uint8_t>(m.need(fl, 5, 16, 0, 1, "apu2mpu_dsel", w));
  rec.commits.clear();

  // F: by index (no two ports write one register in a cycle).
  const std::uint32_t fc_en = m.need(fl, 6, 2, 0, kFCommitPorts, "dbg_fc_en", w);
  std::array<Commit, kFCommitPorts> f;
  int nf = 0;
  for (int port = 0; port < kFCommitPorts; ++port) {
    if (!((fc_en >> port) & 1)) continue;
    const std::string which = " (port " + std::to_string(port) + ")";
    const Commit c{Commit::Kind::FReg,
                   static_cast<std::uint16_t>(m.need(fl, 7, 2, 6 * port, 6, "dbg_fc_idx" + which, w)),
                   m.need(fl, 8, 16, 24 * port, 24, "dbg_fc_val" + which, w)};
    int j = nf++;
    for (; j > 0 && f[j - 1].index > c.index; --j) f[j] = f[j - 1];
    f[j] = c;
  }
  for (int i = 0; i < nf; ++i) rec.commits.push_back(f[i]);

  // A: by index.
  const std::uint32_t ac_en = m.need(fl, 9, 2, 0, 2, "dbg_ac_en", w);
  std::array<Commit, 2> a;
  int na = 0;
  for (int port = 0; port < 2; ++port) {
    if (!((ac_en >> port) & 1)) continue;
    const std::string which = " (port " + std::to_string(port) + ")";
    a[na++] = {Commit::Kind::AReg, static_cast<std::uint16_t>(m.need(fl, 10, 2, 4 * port, 4, "dbg_ac_idx" + which, w)),
               m.need(fl, 11, 16, 16 * port, 16, "dbg_ac_val" + which, w)};
  }
  if (na == 2 && a[1].index < a[0].index) std::swap(a[0], a[1]);
  for (int i = 0; i < na; ++i) rec.commits.push_back(a[i]);

  if (m.need(fl, 12, 16, 0, 1, "dbg_mc_en", w))
    rec.commits.push_back({Commit::Kind::Mem, static_cast<std::uint16_t>(m.need(fl, 13, 16, 0, 12, "dbg_mc_addr", w)),
                           m.need(fl, 14, 16, 0, 24, "dbg_mc_val", w)});
  if (m.need(fl, 15, 16, 0, 1, "dbg_cc_en", w))
    rec.commits.push_back({Commit::Kind::Cc, 0, m.need(fl, 16, 16, 0, 4, "dbg_cc_val", w)});
  if (m.need(fl, 17, 16, 0, 1, "dbg_flags_en", w))
    rec.commits.push_back({Commit::Kind::Flags, 0, m.need(fl, 18, 16, 0, 5, "dbg_flags_val", w)});

  m.clocked();
  m.parse_status(fl, 19, "after cycle " + std::to_string(rec.cycle) + ", pc " + hex(rec.pc, 3));
  ++m.cycle;
}

namespace {
// Cycles a run() request clocks at most: a reply at least every 20 s of the
// RTL (about 1000 cycles a second) or 2 minutes of a netlist, well inside
// the reply timeout.
constexpr std::uint64_t kMaxBurst = 20'000;
}

// The bench's "r N" (run) or "u N" (until the data bank is taken) in bursts
// of at most kMaxBurst cycles; the cycles run.
std::uint64_t IcarusEngine::run_bursts(char op, std::uint64_t max_cycles) {
  Impl& m = *impl_;
  const char name[2] = {op, '\0'};
  std::uint64_t total = 0;
  while (total < max_cycles) {
    const std::uint64_t n = std::min(max_cycles - total, kMaxBurst);
    char buf[32];
    std::snprintf(buf, sizeof buf, "%c %llx", op, static_cast<unsigned long long>(n));
    const std::string w = "running from cycle " + std::to_string(m.cycle);
    const std::string reply = m.request(buf, w);
    const Fields fl(reply, 13, name);
    const std::uint64_t k = std::strtoull(fl.token(0).c_str(), nullptr, 16);
    m.cycle += k;
    total += k;
    m.clocked();
    m.parse_status(fl, 1, "after cycle " + std::to_string(m.cycle));
    if (k < n) break;
  }
  return total;
}

std::uint64_t IcarusEngine::run(std::uint64_t max_cycles) { return run_bursts('r', max_cycles); }

std::uint64_t IcarusEngine::run_until_data_taken(std::uint64_t max_cycles) { return run_bursts('u', max_cycles); }

// ---- state between cycles -----------------------------------------------------------

// The register as the next word reads it (RtlEngine::freg): a result
// completing in the coming cycle is bypassed.
std::uint32_t IcarusEngine::freg(int i) const {
  Impl& m = *impl_;
  i &= kNumFRegs - 1;
  m.ensure_status();
  for (int port = 0; port < kFCompletionPorts; ++port)
    if (((m.status.fc_en >> port) & 1) && m.status.fc_idx[port] == i) return m.status.fc_val[port];
  m.ensure_regs();
  return m.f[static_cast<std::size_t>(i)];
}

std::uint16_t IcarusEngine::areg(int i) const {
  impl_->ensure_regs();
  return impl_->a[static_cast<std::size_t>(i & (kNumARegs - 1))];
}

const ApuCounters& IcarusEngine::counters() const {
  Impl& m = *impl_;
  const std::string w = m.where();
  const std::string reply = m.request("k", w);
  if (reply.size() != 256 * 16)
    throw IcarusError("icarus engine: a malformed reply to 'k' (" + std::to_string(reply.size()) + " characters)");
  m.counters = {};
  for (unsigned key = 0; key < 256; ++key) {
    const std::uint64_t n = std::strtoull(reply.substr(key * 16, 16).c_str(), nullptr, 16);
    const unsigned stall = key >> 4, units = key & 7;
    if (key & 8) m.counters.issued += n;
    for (int u = 0; u < 3; ++u) m.counters.unit_ops[u] += (units >> u & 1) * n;
    if (stall != static_cast<unsigned>(Stall::None) && stall < static_cast<unsigned>(kStallKinds))
      m.counters.stalls[stall] += n;
  }
  return m.counters;
}

}  // namespace mc1::apu
