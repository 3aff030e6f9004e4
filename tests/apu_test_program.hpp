// What the hand-timed APU tests share (tests/apu_hand_timed_test.cpp runs
// them on both engines; tests/apu_iss_test.cpp, tests/apu_rtl_test.cpp hold
// what only one engine has): microword builders and a program runner that
// keeps every cycle's record. The expected timings are derived from
// docs/apu-isa.md, not from either engine.
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "apu_driver.hpp"
#include "apu_engine.hpp"
#include "microword.hpp"

namespace mc1::apu::apu_test {

constexpr std::uint32_t kOne = 0x3F0000, kTwo = 0x400000, kThree = 0x408000;

// Word builders: one slot each; combine with `|`.
inline MicroWord nop() { return {}; }
inline MicroWord ialu(IntOp op, int d, int s, int t, std::uint16_t imm) {
  MicroWord w;
  w.i = {op, std::uint8_t(d), std::uint8_t(s), std::uint8_t(t), imm};
  return w;
}
inline MicroWord lif(int d, std::uint16_t imm) { return ialu(IntOp::Lif, d, 0, 0, imm); }
inline MicroWord li(int d, std::uint16_t imm) { return ialu(IntOp::Li, d, 0, 0, imm); }
inline MicroWord mul(int d, int a, int b) {
  MicroWord w;
  w.m = {true, std::uint8_t(d), std::uint8_t(a), std::uint8_t(b)};
  return w;
}
inline MicroWord addu(AddOp op, int d, int a, int b) {
  MicroWord w;
  w.a = {true, op, std::uint8_t(d), std::uint8_t(a), std::uint8_t(b)};
  return w;
}
inline MicroWord func(FuncOp op, int d, int a) {
  MicroWord w;
  w.f = {true, op, std::uint8_t(d), std::uint8_t(a)};
  return w;
}
inline MicroWord mem(MemOp op, int f, int base, int disp) {
  MicroWord w;
  w.d = {op, std::uint8_t(f), std::uint8_t(base), std::int8_t(disp)};
  return w;
}
inline MicroWord seq(SeqOp op, int r = 0, int target = 0) {
  MicroWord w;
  w.s = {op, std::uint8_t(r), std::uint16_t(target)};
  return w;
}
inline MicroWord halt() { return seq(SeqOp::Halt); }

// Merges the non-empty slots of b into a.
inline MicroWord operator|(MicroWord a, const MicroWord& b) {
  if (b.m.en) a.m = b.m;
  if (b.a.en) a.a = b.a;
  if (b.f.en) a.f = b.f;
  if (b.d.op != MemOp::None) a.d = b.d;
  if (b.i.op != IntOp::None) a.i = b.i;
  if (b.s.op != SeqOp::Next) a.s = b.s;
  return a;
}

inline std::vector<Encoded> encode(const std::vector<MicroWord>& prog) {
  std::vector<Encoded> out;
  for (const auto& w : prog) out.push_back(w.encode());
  return out;
}

// A program loaded into the MPU's bank of `engine`, handed over and started
// at 0; every stepped cycle's record is kept. The engine outlives it.
struct EngineProgram {
  ApuEngine* apu;
  std::unique_ptr<ApuDriver> drv;
  std::vector<CycleRecord> recs;

  EngineProgram(ApuEngine& engine, const std::vector<MicroWord>& prog)
      : apu(&engine), drv(std::make_unique<ApuDriver>(engine)) {
    drv->load_program(encode(prog));
    drv->hand_over_program();
    drv->start(0);
    // The start's fetch and decode cycles (docs/apu-isa.md "Timing"): the
    // program RAM reads the word at 0, then it is decoded; nothing issues
    // (`fetch`). recs[0] is the first word's cycle.
    for (int i = 0; i < kStartFetchCycles; ++i) {
      CycleRecord rec;
      apu->step(rec);
      EXPECT_FALSE(rec.issued);
      EXPECT_EQ(rec.stall, Stall::Fetch);
      EXPECT_EQ(rec.pc, 0);
    }
  }
  // Steps while running (at most `limit` cycles), then `extra` more.
  EngineProgram& go(int limit = 1000, int extra = 0) {
    for (int i = 0; i < limit && apu->state() == RunState::Running; ++i) step();
    for (int i = 0; i < extra; ++i) step();
    return *this;
  }
  const CycleRecord& step() {
    recs.emplace_back();
    apu->step(recs.back());
    return recs.back();
  }
  std::vector<Stall> stalls() const {
    std::vector<Stall> out;
    for (const auto& r : recs) out.push_back(r.stall);
    return out;
  }
  // Issued words' pcs, -1 for a cycle that issued nothing.
  std::vector<int> pcs() const {
    std::vector<int> out;
    for (const auto& r : recs) out.push_back(r.issued ? r.pc : -1);
    return out;
  }
};

}  // namespace mc1::apu::apu_test
