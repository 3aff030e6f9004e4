// The ISS's plans (apu_iss.hpp, Iss::PlanStep; docs/apu-tools.md "Plans"):
// a body's direct words as dataflow, their MULs and ADD/SUBs eight at a time
// through fp24::lanes.
//
// Why the order may change: every write of a direct word lands within the
// body, and the scoreboard holds back any word that reads or overwrites a
// register with a write in flight (raw, waw), so the body's words give the
// state that running them one after another in program order, each write
// made at once, gives (body_direct_words does just that). Renaming each
// value to a slot of its own leaves only the true dependences: an op reads
// the values its operands held just before its word, and any order that
// runs each op after the ops that made them gives the same values. FLAGS is
// an OR, which no order changes. The ops that touch the data bank, the A
// registers or CC keep their program order among themselves.
#include <algorithm>

#include "apu_iss.hpp"
#include "apu_iss_inline.hpp"

namespace mc1::apu {

namespace {

// Values while a plan is built: 0..63 the F registers at the body's start,
// kMade + k the result of op k.
constexpr int kMade = kNumFRegs;

struct PlanOp {
  std::uint8_t kind;
  std::uint8_t word;
  int a, b;        // operand values, or -1
  bool neg;        // kPlanAdd: a SUB
  bool makes;      // it has a result value
  int depth;       // the plan runs it after every op of a lesser depth
  int slot = -1;   // its result's slot
};

}  // namespace

void Iss::build_plan(BodyBank& bb, Body& body) const {
  const BodyWord* words = bb.words.data() + body.first;
  const std::uint32_t count = std::min<std::uint32_t>(body.direct, body.n - body.branch);
  int lane_ops = 0;
  for (std::uint32_t k = 0; k < count; ++k) {
    const int a = words[k].shape & 6;
    lane_ops += (words[k].shape & 1) + (a == 2 || a == 4);
  }
  if (count == 0 || lane_ops < plan_min_ops_) return;

  // The ops in program order (within a word: its reads, then its writes in
  // body_word's order M, A, F, LD, I), each with the values it reads and
  // the least depth its order with the ops before it allows (steps of one
  // depth keep program order):
  // - a LD or ST after each earlier ST, and a ST after each earlier LD,
  //   that may touch its address (another base register, or its own with
  //   the same displacement: a body's bases keep their value until its
  //   last LD/ST);
  // - the I slot's ops (they read and write A registers) after each
  //   other, and after each LD/ST on the base register they write;
  // - a CMP after the CMPs before it (CC is the last one's).
  std::vector<PlanOp> ops;
  std::array<int, kNumFRegs> cur;  // the value each register holds
  for (int r = 0; r < kNumFRegs; ++r) cur[static_cast<std::size_t>(r)] = r;
  const auto depth_of = [&ops](int v) { return v < kMade ? 0 : ops[static_cast<std::size_t>(v - kMade)].depth + 1; };
  struct Access {
    int depth;
    std::uint8_t base;
    std::int8_t disp;
    bool store;
  };
  std::vector<Access> accesses;
  std::array<int, kNumARegs> base_used{};  // the depth of the last LD/ST on each base register
  int int_chain = 0, cmp_chain = 0;
  for (std::uint32_t k = 0; k < count; ++k) {
    const BodyWord& bw = words[k];
    const MicroWord& w = bw.w;
    std::array<std::pair<int, int>, 5> writes;  // register, op
    int nw = 0;
    const auto op = [&](std::uint8_t kind, int a, int b, bool makes, int after) {
      const int d = std::max({a >= 0 ? depth_of(a) : 0, b >= 0 ? depth_of(b) : 0, after});
      ops.push_back({kind, static_cast<std::uint8_t>(k), a, b, false, makes, d});
      return static_cast<int>(ops.size() - 1);
    };
    const auto access = [&](bool store, int a) {
      int after = 0;
      for (const Access& x : accesses)
        if ((store || x.store) && (x.base != w.d.base || x.disp == w.d.disp)) after = std::max(after, x.depth);
      const int i = op(store ? kPlanSt : kPlanLd, a, -1, !store, after);
      const int d = ops[static_cast<std::size_t>(i)].depth;
      accesses.push_back({d, w.d.base, w.d.disp, store});
      base_used[w.d.base & 15] = std::max(base_used[w.d.base & 15], d);
      return i;
    };
    if (w.m.en) writes[nw++] = {w.m.d, op(kPlanMul, cur[w.m.a], cur[w.m.b], true, 0)};
    const int a_shape = bw.shape & 6;
    if (a_shape == 2 || a_shape == 4) {
      const int i = op(kPlanAdd, cur[w.a.a], cur[w.a.b], true, 0);
      ops[static_cast<std::size_t>(i)].neg = a_shape == 4;
      writes[nw++] = {w.a.d, i};
    } else if (a_shape == 6 && w.a.op == AddOp::Cmp) {
      cmp_chain = ops[static_cast<std::size_t>(op(kPlanCmp, cur[w.a.a], cur[w.a.b], false, cmp_chain))].depth;
    } else if (a_shape == 6) {
      writes[nw++] = {w.a.d, op(kPlanAddUnit, cur[w.a.a], cur[w.a.b], true, 0)};
    }
    if (w.f.en) writes[nw++] = {w.f.d, op(kPlanFunc, cur[w.f.a], -1, true, 0)};
    if (w.d.op == MemOp::Ld) {
      writes[nw++] = {w.d.f, access(false, -1)};
    } else if (w.d.op == MemOp::St) {
      access(true, cur[w.d.f]);
    }
    if (bw.islot == kISlotA) {
      const int i = op(kPlanIntA, w.i.op == IntOp::Movfa ? cur[w.i.imm & 63] : -1, -1, false,
                       std::max(int_chain, base_used[w.i.d & 15]));
      int_chain = ops[static_cast<std::size_t>(i)].depth;
    } else if (bw.islot == kISlotF) {
      const int i = op(kPlanMovF, -1, -1, true, int_chain);
      int_chain = ops[static_cast<std::size_t>(i)].depth;
      writes[nw++] = {w.i.d & 63, i};
    }
    for (int j = 0; j < nw; ++j) cur[static_cast<std::size_t>(writes[j].first)] = kMade + writes[j].second;
  }

  Plan plan;
  plan.first_step = static_cast<std::uint32_t>(bb.steps.size());
  plan.first_batch = static_cast<std::uint32_t>(bb.batches.size());
  plan.first_back = static_cast<std::uint32_t>(bb.back.size());
  plan.words = static_cast<std::uint8_t>(count);
  int next = kNumFRegs;  // the next free slot
  const auto slot_of = [&ops](int v) { return v < kMade ? v : ops[static_cast<std::size_t>(v - kMade)].slot; };
  const auto u16 = [](int x) { return static_cast<std::uint16_t>(x); };
  int max_depth = 0;
  for (const PlanOp& o : ops) max_depth = std::max(max_depth, o.depth);
  // The latest depth of each lane op: one before the earliest of its
  // readers' (a lane op's reader at its own latest), the last for one the
  // plan's words never read.
  std::vector<int> latest(ops.size(), max_depth);
  for (std::size_t i = ops.size(); i-- > 0;) {
    const PlanOp& o = ops[i];
    const int at = o.kind == kPlanMul || o.kind == kPlanAdd ? latest[i] : o.depth;
    for (const int v : {o.a, o.b}) {
      if (v < kMade) continue;
      int& l = latest[static_cast<std::size_t>(v - kMade)];
      l = std::min(l, at - 1);
    }
  }
  // Steps by depth: at each, the ops that keep program order and the other
  // one-by-one ops, in program order; then, of each kind, the lane ops that
  // can wait no longer, in batches of eight, the last batch filled with ops
  // that could wait (their operands made at a lesser depth), those that
  // must go soonest first. Every value an op reads is made by an earlier
  // step.
  std::vector<int> placed(ops.size(), -1);
  const auto ready = [&](int v, int d) {
    if (v < kMade) return true;
    const int p = placed[static_cast<std::size_t>(v - kMade)];
    return p >= 0 && p < d;
  };
  std::vector<std::size_t> take;
  for (int d = 0; d <= max_depth; ++d) {
    for (std::size_t i = 0; i < ops.size(); ++i) {
      PlanOp& o = ops[i];
      if (o.depth != d || o.kind == kPlanMul || o.kind == kPlanAdd) continue;
      if (o.makes) o.slot = next++;
      placed[i] = d;
      bb.steps.push_back({o.kind, o.word, u16(o.a >= 0 ? slot_of(o.a) : 0), u16(o.b >= 0 ? slot_of(o.b) : 0),
                          u16(o.makes ? o.slot : 0)});
    }
    for (const std::uint8_t kind : {kPlanMul, kPlanAdd}) {
      take.clear();
      for (std::size_t i = 0; i < ops.size(); ++i)
        if (ops[i].kind == kind && placed[i] < 0 && latest[i] == d) take.push_back(i);
      if (take.empty()) continue;
      const std::size_t forced = take.size();
      for (std::size_t i = 0; i < ops.size(); ++i)
        if (ops[i].kind == kind && placed[i] < 0 && latest[i] > d && ready(ops[i].a, d) && ready(ops[i].b, d))
          take.push_back(i);
      std::stable_sort(take.begin() + static_cast<std::ptrdiff_t>(forced), take.end(),
                       [&latest](std::size_t x, std::size_t y) { return latest[x] < latest[y]; });
      take.resize(std::min(take.size(), (forced + fp24::lanes::kLanes - 1) / fp24::lanes::kLanes * fp24::lanes::kLanes));
      fp24::lanes::Batch batch{};
      const auto flush = [&]() {
        if (batch.n < (kind == kPlanMul ? 4 : 3)) {
          for (unsigned l = 0; l < batch.n; ++l)
            bb.steps.push_back({static_cast<std::uint8_t>(kind == kPlanMul ? kPlanMul1 : (batch.neg >> l) & 1 ? kPlanSub1 : kPlanAdd1), 0, batch.a[l], batch.b[l], u16(next + static_cast<int>(l))});
          next += fp24::lanes::kLanes;
          batch = fp24::lanes::Batch{};
          return;
        }
        bb.steps.push_back({kind, 0, u16(static_cast<int>(bb.batches.size() - plan.first_batch)), 0, u16(next)});
        bb.batches.push_back(batch);
        next += fp24::lanes::kLanes;
        batch = fp24::lanes::Batch{};
      };
      for (const std::size_t i : take) {
        PlanOp& o = ops[i];
        const unsigned lane = batch.n++;
        batch.a[lane] = u16(slot_of(o.a));
        batch.b[lane] = u16(slot_of(o.b));
        batch.neg = static_cast<std::uint8_t>(batch.neg | (o.neg ? 1u << lane : 0u));
        o.slot = next + static_cast<int>(lane);
        placed[i] = d;
        if (batch.n == fp24::lanes::kLanes) flush();
      }
      if (batch.n > 0) flush();
    }
  }
  for (int r = 0; r < kNumFRegs; ++r) {
    const int v = cur[static_cast<std::size_t>(r)];
    if (v < kMade) continue;
    bb.back.push_back(u16(r));
    bb.back.push_back(u16(slot_of(v)));
  }
  if (next > kPlanSlots) {  // more values than vals_ holds: no plan
    bb.steps.resize(plan.first_step);
    bb.batches.resize(plan.first_batch);
    bb.back.resize(plan.first_back);
    return;
  }
  plan.nsteps = static_cast<std::uint16_t>(bb.steps.size() - plan.first_step);
  plan.nback = static_cast<std::uint16_t>((bb.back.size() - plan.first_back) / 2);
  body.plan = static_cast<std::int16_t>(bb.plans.size());
  bb.plans.push_back(plan);
}

// The plan's words: as body_direct_words would run them (each write at once).
void Iss::run_plan(const BodyBank& bb, const Plan& plan, const BodyWord* words) {
  std::uint32_t* const v = vals_.data();
  std::copy_n(f_.data(), kNumFRegs, v);
  std::uint32_t fl = flags_;
  std::array<std::uint32_t, kDataWords>& data = data_[static_cast<std::size_t>(dsel_)];
  const fp24::lanes::Batch* const batches = bb.batches.data() + plan.first_batch;
  const PlanStep* s = bb.steps.data() + plan.first_step;
  for (const PlanStep* const end = s + plan.nsteps; s != end; ++s) {
    const MicroWord& w = words[s->word].w;
    switch (s->kind) {
      case kPlanMul: fl |= fp24::lanes::mul(v, batches[s->a], v + s->dst); break;
      case kPlanAdd: fl |= fp24::lanes::add(v, batches[s->a], v + s->dst); break;
      case kPlanMul1: {
        const fp24::Result r = fp24::inl::mul24(v[s->a], v[s->b]);
        v[s->dst] = r.value;
        fl |= r.flags;
        break;
      }
      case kPlanAdd1: {
        const fp24::Result r = fp24::inl::add24(v[s->a], v[s->b]);
        v[s->dst] = r.value;
        fl |= r.flags;
        break;
      }
      case kPlanSub1: {
        const fp24::Result r = fp24::inl::sub24(v[s->a], v[s->b]);
        v[s->dst] = r.value;
        fl |= r.flags;
        break;
      }
      case kPlanLd: v[s->dst] = data[static_cast<std::uint16_t>(a_[w.d.base] + w.d.disp)]; break;
      case kPlanSt: data[static_cast<std::uint16_t>(a_[w.d.base] + w.d.disp)] = v[s->a]; break;
      case kPlanAddUnit: {
        const fp24::Result r = add_unit(w.a.op, v[s->a], v[s->b]);
        v[s->dst] = r.value;
        fl |= r.flags;
        break;
      }
      case kPlanCmp: {
        const fp24::Result r = fp24::inl::cmp(v[s->a], v[s->b]);
        cc_ = r.value;
        fl |= r.flags;
        break;
      }
      case kPlanFunc: {
        const fp24::Result r = func_unit(w.f.op, v[s->a]);
        v[s->dst] = r.value;
        fl |= r.flags;
        break;
      }
      case kPlanIntA: {
        std::uint16_t x = static_cast<std::uint16_t>(v[s->a]);  // MOVFA's F operand
        if (w.i.op != IntOp::Movfa) int_value(w.i, x);
        a_[w.i.d & 15] = x;
        break;
      }
      default:  // kPlanMovF
        v[s->dst] = w.i.op == IntOp::Movaf ? a_[w.i.s] : (std::uint32_t{w.i.imm} << 8) & kMask24;
        break;
    }
  }
  const std::uint16_t* back = bb.back.data() + plan.first_back;
  for (std::uint32_t k = 0; k < plan.nback; ++k, back += 2) f_[back[0]] = v[back[1]];
  flags_ = fl;
  ++plans_run_;
}

}  // namespace mc1::apu
