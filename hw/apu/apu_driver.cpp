// The MPU-side APU driver: the same calls on the ISS or the RTL core.
#include "apu_driver.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>

#include "apu_iss.hpp"
#include "disasm.hpp"

namespace mc1::apu {
namespace {

std::string hex(unsigned v, int digits) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%0*x", digits, v);
  return buf;
}

// A data file fills a bank at most: 4096 words of 6 hex digits, 28 KB and
// its comments (docs/apu-tools.md). The limit bounds what a file that never
// ends (/dev/zero, a FIFO) makes the tools hold.
constexpr std::size_t kMaxDataFileBytes = std::size_t{16} << 20;  // 16 MiB

// The whole data file, read to at most one byte past kMaxDataFileBytes.
std::string read_data_text(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open data file");
  std::string text;
  char buf[1 << 16];
  while (text.size() <= kMaxDataFileBytes) {
    in.read(buf, std::streamsize(std::min(sizeof buf, kMaxDataFileBytes + 1 - text.size())));
    text.append(buf, std::size_t(in.gcount()));
    if (!in) break;
  }
  if (text.size() > kMaxDataFileBytes)
    throw std::runtime_error(path + ": over " + std::to_string(kMaxDataFileBytes >> 20) +
                             " MiB, too large for a data file");
  return text;
}

}  // namespace

ApuDriver::ApuDriver(ApuEngine& engine) : engine_(engine), iss_(dynamic_cast<Iss*>(&engine)) {
  for (auto& bank : shadow_) bank.assign(kProgramWords, Encoded{});
  if (iss_) {
    psel_ = iss_->psel();
    pc_ = iss_->pc();
  }
  rec_.commits.reserve(16);
}

void ApuDriver::load_program(const std::vector<Encoded>& words, std::uint16_t base) {
  access();
  if (base + words.size() > static_cast<std::size_t>(kProgramWords))
    fail(ApuError::Kind::Usage, "load_program: " + std::to_string(words.size()) + " words at " +
                                    std::to_string(base) + " do not fit the 1024-word bank");
  const int bank = (iss_ ? iss_->psel() : psel_) ^ 1;
  for (std::size_t i = 0; i < words.size(); ++i) {
    const auto addr = static_cast<std::uint16_t>(base + i);
    engine_.write_program(addr, words[i]);
    shadow_[bank][addr] = words[i];
  }
}

void ApuDriver::hand_over_program() {
  access();
  if (on_hand_over_) {
    const int bank = (iss_ ? iss_->psel() : psel_) ^ 1;
    on_hand_over_(bank, shadow_[bank]);
  }
  engine_.hand_over_program();
}

void ApuDriver::load_data(std::uint16_t addr, const std::uint32_t* values, std::size_t n) {
  if (addr + n > static_cast<std::size_t>(kDataWords)) {
    access();
    fail(ApuError::Kind::Usage, "load_data: " + std::to_string(n) + " words at " + std::to_string(addr) +
                                    " do not fit the 4096-word bank");
  }
  access_bank();
  engine_.write_data_block(addr, values, n);
}

std::vector<std::uint32_t> ApuDriver::read_results(std::uint16_t addr, std::size_t n) const {
  std::vector<std::uint32_t> out(n);
  read_results(addr, out.data(), n);
  return out;
}

void ApuDriver::read_results(std::uint16_t addr, std::uint32_t* out, std::size_t n) const {
  if (addr + n > static_cast<std::size_t>(kDataWords)) {
    access();
    fail(ApuError::Kind::Usage, "read_results: " + std::to_string(n) + " words at " + std::to_string(addr) +
                                    " do not fit the 4096-word bank");
  }
  access_bank();
  engine_.read_data_block(addr, out, n);
}

void ApuDriver::start(std::uint16_t pc) {
  access();
  if (engine_.state() == RunState::Running) fail(ApuError::Kind::Usage, "start: the APU is running");
  if (engine_.program_ready()) psel_ ^= 1;
  engine_.start(pc);
  pc_ = pc % kProgramWords;
  last_stall_ = Stall::None;
}

void ApuDriver::access_bank() const {
  if (!data_pending_ && bank_hook_) return bank_hook_();
  access();
  data_pending_ = engine_.data_ready();  // a hand-over not yet taken
}

std::uint64_t ApuDriver::clock(std::uint64_t cycles, bool until_data_taken) {
  if (!observer_) {
    // The engine's fast path. A program hand-over that was pending before
    // and is gone after was taken by a SWAPP: the APU's bank flipped.
    const bool ready_before = engine_.program_ready();
    const std::uint64_t n = until_data_taken ? engine_.run_until_data_taken(cycles) : engine_.run(cycles);
    if (iss_) {
      psel_ = iss_->psel();
      pc_ = iss_->pc();
    } else if (ready_before && !engine_.program_ready()) {
      psel_ ^= 1;
    }
    pc_known_ = n == 0;
    return n;
  }
  std::uint64_t n = 0;
  while (n < cycles && engine_.state() == RunState::Running && (!until_data_taken || engine_.data_ready())) {
    engine_.step(rec_);
    ++n;
    pc_ = rec_.pc;
    last_stall_ = rec_.stall;
    // The record shows the bank before this cycle's swap.
    psel_ = rec_.psel;
    if (rec_.issued && MicroWord::decode(shadow_[psel_][rec_.pc]).s.op == SeqOp::Swapp) psel_ ^= 1;
    observer_(rec_);
  }
  pc_known_ = true;
  return n;
}

std::uint64_t ApuDriver::run(std::uint64_t cycles) {
  access();
  return clock(cycles);
}

std::uint64_t ApuDriver::run_until_data_taken(std::uint64_t cycles) {
  access();
  return clock(cycles, true);
}

std::uint64_t ApuDriver::run_until_done(std::uint64_t max_cycles, const std::function<void()>& mpu,
                                        std::uint64_t mpu_interval) {
  begin_run();
  if (mpu_interval == 0) mpu_interval = 1;
  std::uint64_t done = 0;
  while (engine_.state() == RunState::Running && done < max_cycles) {
    std::uint64_t chunk = max_cycles - done;
    if (mpu) {
      if (engine_.cycle() % mpu_interval == 0) mpu();
      chunk = std::min(chunk, mpu_interval - engine_.cycle() % mpu_interval);
    }
    done += clock(chunk);
  }
  return end_run(done, max_cycles);
}

void ApuDriver::begin_run() {
  access();
  if (engine_.state() != RunState::Running)
    fail(ApuError::Kind::NotRunning, "run_until_done: the APU was not started");
  probe_cycle_ = 0;
}

std::uint64_t ApuDriver::end_run(std::uint64_t done, std::uint64_t max_cycles) {
  if (!pc_known_ && engine_.state() != RunState::Halted) {
    // The fast path keeps no records. Which word faulted or is stuck, and
    // on what: the ISS answers through a copy clocked once; any other engine
    // is clocked once more itself (a faulted or stuck APU stays so).
    CycleRecord r;
    if (iss_) {
      auto probe = std::make_unique<Iss>(*iss_);
      probe->step(r);
    } else {
      probe_cycle_ = engine_.cycle();
      engine_.step(r);
    }
    pc_ = r.pc;
    last_stall_ = r.stall;
  }
  switch (engine_.state()) {
    case RunState::Halted: {
      CycleRecord settle;
      for (int i = 0; i < kSettleCycles; ++i) engine_.step(settle);
      return done;
    }
    case RunState::Faulted:
      fail(ApuError::Kind::Fault, std::string("APU fault ") + fault_name(engine_.fault()));
    case RunState::Running:
      fail(ApuError::Kind::CycleLimit, "APU still running after " + std::to_string(max_cycles) +
                                           " cycles (cycle limit)" +
                                           (last_stall_ != Stall::None
                                                ? std::string(", stalled: ") + stall_name(last_stall_)
                                                : std::string()));
    case RunState::Idle: break;
  }
  fail(ApuError::Kind::NotRunning, "run_until_done: the APU is idle");
}

void ApuDriver::fail(ApuError::Kind kind, const std::string& why) const {
  std::string what = why;
  Fault f = Fault::None;
  std::uint64_t cycle = probe_cycle_ ? probe_cycle_ : engine_.cycle();
  if (kind == ApuError::Kind::Fault || kind == ApuError::Kind::CycleLimit) {
    cycle = cycle > 0 ? cycle - 1 : 0;  // the last cycle of the run
    f = engine_.fault();
    what += " at cycle " + std::to_string(cycle) + ", pc " + hex(pc_, 3) + " (bank " + std::to_string(psel_) +
            "): " + disassemble(shadow_[psel_][pc_]);
    if (kind == ApuError::Kind::CycleLimit && last_stall_ == Stall::Bank)
      what += "  [waiting for the MPU's hand_over_data()/hand_over_program()]";
  }
  throw ApuError(kind, f, cycle, pc_, what);
}

std::vector<std::pair<std::uint16_t, std::uint32_t>> read_data_file(const std::string& path) {
  std::istringstream in(read_data_text(path));
  std::vector<std::pair<std::uint16_t, std::uint32_t>> out;
  std::string line;
  unsigned long addr = 0;
  for (int lineno = 1; std::getline(in, line); ++lineno) {
    line = line.substr(0, line.find('#'));
    std::istringstream words(line);
    std::string tok;
    while (words >> tok) {
      const bool at = tok[0] == '@';
      const std::string digits = at ? tok.substr(1) : tok;
      std::size_t used = 0;
      unsigned long v = 0;
      try {
        v = std::stoul(digits, &used, 16);
      } catch (const std::exception&) {
        used = 0;
      }
      if (digits.empty() || used != digits.size())
        throw std::runtime_error(path + ":" + std::to_string(lineno) + ": not a hex word: '" + tok + "'");
      if (at) {
        addr = v;
      } else {
        if (v > 0xFFFFFF)
          throw std::runtime_error(path + ":" + std::to_string(lineno) + ": '" + tok + "' is wider than 24 bits");
        if (addr >= static_cast<unsigned long>(kDataWords))
          throw std::runtime_error(path + ":" + std::to_string(lineno) + ": address " + std::to_string(addr) +
                                   " past the 4096-word bank");
        out.emplace_back(static_cast<std::uint16_t>(addr++), static_cast<std::uint32_t>(v));
      }
    }
  }
  return out;
}

}  // namespace mc1::apu
