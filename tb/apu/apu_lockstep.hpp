// Lockstep co-simulation of two APU engines (Nyuzi-style cosimulation):
// both clock once per step, and the first cycle whose records differ (pc,
// issue, stall reason, bank selects, any commit) or whose run state, fault or
// hand-over flags differ is reported with cycle, pc, the disassembled word
// and both values. Header-only so that the tool and the tests share it.
#pragma once

#include <algorithm>
#include <cstdio>
#include <functional>
#include <optional>
#include <string>

#include "apu_engine.hpp"
#include "apu_iss.hpp"
#include "disasm.hpp"

namespace mc1::apu {

inline std::string hex_text(std::uint32_t v, int digits) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%0*x", digits, v);
  return buf;
}

inline std::string commit_text(const Commit& c) {
  switch (c.kind) {
    case Commit::Kind::FReg: return "F" + std::to_string(c.index) + "=" + hex_text(c.value, 6);
    case Commit::Kind::AReg: return "A" + std::to_string(c.index) + "=" + hex_text(c.value, 4);
    case Commit::Kind::Mem: return "M[" + hex_text(c.index, 3) + "]=" + hex_text(c.value, 6);
    case Commit::Kind::Cc: return "CC=" + hex_text(c.value, 1);
    case Commit::Kind::Flags: return "FLAGS=" + hex_text(c.value, 2);
  }
  return "?";
}

inline std::string record_text(const CycleRecord& r) {
  std::string s = "pc " + hex_text(r.pc, 3) + (r.issued ? " issued" : " not issued");
  if (r.stall != Stall::None) s += std::string(" stall ") + stall_name(r.stall);
  s += " psel " + std::to_string(r.psel) + " dsel " + std::to_string(r.dsel) + " commits {";
  for (std::size_t i = 0; i < r.commits.size(); ++i) s += (i ? " " : "") + commit_text(r.commits[i]);
  return s + "}";
}

struct Divergence {
  std::uint64_t cycle = 0;
  std::uint16_t pc = 0;
  std::uint8_t psel = 0;
  std::string word;   // disassembly of the word at pc (or its hex)
  std::string field;  // what differs, e.g. "commit 0" or "stall"
  std::string a, b;   // the two values
  std::string a_record, b_record;

  std::string report(const std::string& a_name, const std::string& b_name) const {
    std::string s = "divergence at cycle " + std::to_string(cycle) + ", pc " + hex_text(pc, 3) + " (bank " +
                    std::to_string(psel) + "): " + word + "\n";
    s += "  " + field + ": " + a_name + " " + a + "  vs  " + b_name + " " + b + "\n";
    if (!a_record.empty()) {
      s += "  " + a_name + ": " + a_record + "\n";
      s += "  " + b_name + ": " + b_record + "\n";
    }
    return s;
  }
};

class Lockstep {
 public:
  // program_word(bank, addr) disassembles reports; by default it asks
  // whichever engine is the ISS.
  Lockstep(ApuEngine& a, ApuEngine& b, std::function<Encoded(int, std::uint16_t)> program_word = {})
      : a_(a), b_(b), program_word_(std::move(program_word)) {
    ra_.commits.reserve(16);
    rb_.commits.reserve(16);
    if (!program_word_) {
      const Iss* iss = dynamic_cast<const Iss*>(&a);
      if (!iss) iss = dynamic_cast<const Iss*>(&b);
      if (iss) program_word_ = [iss](int bank, std::uint16_t addr) { return iss->program_word(bank, addr); };
    }
  }

  // One cycle on both; the divergence, if this cycle shows one.
  std::optional<Divergence> step() {
    a_.step(ra_);
    b_.step(rb_);
    return compare();
  }

  // The architectural state both engines show the MPU and the registers.
  std::optional<Divergence> compare_state() const {
    auto diff = [&](const std::string& field, std::uint32_t x, std::uint32_t y, int digits) {
      std::optional<Divergence> d;
      if (x != y) d = make(field, hex_text(x, digits), hex_text(y, digits), false);
      return d;
    };
    for (int i = 0; i < kNumFRegs; ++i)
      if (auto d = diff("F" + std::to_string(i), a_.freg(i), b_.freg(i), 6)) return d;
    for (int i = 0; i < kNumARegs; ++i)
      if (auto d = diff("A" + std::to_string(i), a_.areg(i), b_.areg(i), 4)) return d;
    if (auto d = diff("CC", a_.cc(), b_.cc(), 1)) return d;
    if (auto d = diff("FLAGS", a_.flags(), b_.flags(), 2)) return d;
    for (int i = 0; i < kDataWords; ++i)
      if (auto d = diff("MPU data bank word " + hex_text(i, 3), a_.read_data(static_cast<std::uint16_t>(i)),
                        b_.read_data(static_cast<std::uint16_t>(i)), 6))
        return d;
    return std::nullopt;
  }

  const CycleRecord& record_a() const { return ra_; }
  const CycleRecord& record_b() const { return rb_; }
  bool running() const { return a_.state() == RunState::Running || b_.state() == RunState::Running; }

 private:
  std::optional<Divergence> compare() const {
    if (ra_.cycle != rb_.cycle)
      return make("cycle", std::to_string(ra_.cycle), std::to_string(rb_.cycle));
    if (ra_.pc != rb_.pc) return make("pc", hex_text(ra_.pc, 3), hex_text(rb_.pc, 3));
    if (ra_.issued != rb_.issued) return make("issued", ra_.issued ? "1" : "0", rb_.issued ? "1" : "0");
    if (ra_.stall != rb_.stall) return make("stall", stall_name(ra_.stall), stall_name(rb_.stall));
    if (ra_.psel != rb_.psel) return make("psel", std::to_string(ra_.psel), std::to_string(rb_.psel));
    if (ra_.dsel != rb_.dsel) return make("dsel", std::to_string(ra_.dsel), std::to_string(rb_.dsel));
    const std::size_t n = std::max(ra_.commits.size(), rb_.commits.size());
    for (std::size_t i = 0; i < n; ++i) {
      const bool ha = i < ra_.commits.size(), hb = i < rb_.commits.size();
      if (!ha || !hb || !(ra_.commits[i] == rb_.commits[i]))
        return make("commit " + std::to_string(i), ha ? commit_text(ra_.commits[i]) : "(none)",
                    hb ? commit_text(rb_.commits[i]) : "(none)");
    }
    if (a_.state() != b_.state()) return make("state", run_state_name(a_.state()), run_state_name(b_.state()));
    if (a_.fault() != b_.fault()) return make("fault", fault_name(a_.fault()), fault_name(b_.fault()));
    if (a_.data_ready() != b_.data_ready())
      return make("data_ready", std::to_string(a_.data_ready()), std::to_string(b_.data_ready()));
    if (a_.program_ready() != b_.program_ready())
      return make("program_ready", std::to_string(a_.program_ready()), std::to_string(b_.program_ready()));
    return std::nullopt;
  }

  Divergence make(const std::string& field, const std::string& x, const std::string& y, bool records = true) const {
    Divergence d;
    d.cycle = ra_.cycle;
    d.pc = ra_.pc;
    d.psel = ra_.psel;
    d.field = field;
    d.a = x;
    d.b = y;
    d.word = program_word_ ? disassemble(program_word_(ra_.psel, ra_.pc)) : "(word unknown)";
    if (records) {
      d.a_record = record_text(ra_);
      d.b_record = record_text(rb_);
    }
    return d;
  }

  ApuEngine& a_;
  ApuEngine& b_;
  std::function<Encoded(int, std::uint16_t)> program_word_;
  CycleRecord ra_, rb_;
};

}  // namespace mc1::apu
