// Programs aimed at empty bins (coverage_aim.hpp).
#include "coverage_aim.hpp"

#include <fnmatch.h>

#include <functional>

namespace mc1::cov {

namespace {

using apu::RandomOptions;

struct Profile {
  std::string name;
  std::vector<std::string> aims;  // bin patterns
  std::function<void(RandomOptions&)> apply;
};

void slots(RandomOptions& o, unsigned p) {
  o.mul_percent = o.add_percent = o.func_percent = o.mem_percent = o.int_percent = p;
}

const std::vector<Profile>& profiles() {
  static const std::vector<Profile> all = [] {
    std::vector<Profile> v;
    for (int k = 1; k <= 5; ++k) {
      const std::string fault = apu::fault_name(static_cast<apu::Fault>(k));
      std::vector<std::string> aims = {"core.fault." + fault};
      if (k == 1) aims.push_back("core.op.*.op*");  // the reserved codes
      v.push_back({"fault-" + fault, aims, [k](RandomOptions& o) {
                     o.fault_percent = 100;
                     o.fault_kind = k;
                   }});
    }
    v.push_back({"late-handovers", {"core.handover.*", "core.swap.*"}, [](RandomOptions& o) {
                   o.late_percent = 100;
                   o.max_delay = 96;
                 }});
    v.push_back({"hazards", {"core.stall.*", "core.bypass.*"}, [](RandomOptions& o) {
                   o.hazard_percent = 95;
                   o.func_percent = 60;
                 }});
    v.push_back({"branches", {"core.branch.*", "core.bypass.int.*", "core.bypass.cmp.*", "core.stall.cc"},
                 [](RandomOptions& o) {
                   o.branch_percent = 70;
                   o.int_percent = 85;
                   o.add_percent = 80;
                 }});
    v.push_back({"sparse-words", {"core.slots.*"}, [](RandomOptions& o) { slots(o, 15); }});
    v.push_back({"dense-words", {"core.slots.*", "core.bypass.*"}, [](RandomOptions& o) { slots(o, 90); }});
    // Sums and differences of the format's edges: the smallest normals'
    // underflow to a signed zero, the largest's overflow.
    v.push_back({"adder-edges", {"fp24.add.*", "fp24.sub.*"}, [](RandomOptions& o) {
                   slots(o, 0);
                   o.add_percent = 100;
                   o.mem_percent = 30;
                   o.edge_percent = 100;
                 }});
    v.push_back({"unit-ops", {"fp24.*"}, [](RandomOptions& o) {
                   o.mul_percent = o.add_percent = o.func_percent = 90;
                   o.hazard_percent = 20;
                   o.edge_percent = 50;
                 }});
    return v;
  }();
  return all;
}

bool matches(const std::vector<std::string>& patterns, const std::string& bin) {
  for (const auto& p : patterns)
    if (fnmatch(p.c_str(), bin.c_str(), 0) == 0) return true;
  return false;
}

}  // namespace

CoverageAim::CoverageAim(const RandomOptions& base, std::vector<Waiver> waivers)
    : base_(base), waivers_(std::move(waivers)) {}

std::vector<std::string> CoverageAim::empty(const Bins& bins) const {
  std::vector<std::string> out;
  for (const auto& [name, n] : bins.counts())
    if (n == 0 && !waiver_for(waivers_, name)) out.push_back(name);
  return out;
}

RandomOptions CoverageAim::next(const Bins& bins, std::uint64_t index) {
  const std::vector<std::string> holes = empty(bins);
  const auto& all = profiles();
  for (std::size_t k = 0; k < all.size(); ++k) {
    const Profile& p = all[(turn_ + k) % all.size()];
    for (const auto& bin : holes) {
      if (!matches(p.aims, bin)) continue;
      turn_ = (turn_ + k + 1) % all.size();
      RandomOptions o = base_;
      p.apply(o);
      profile_ = p.name;
      return o;
    }
  }
  RandomOptions o = base_;
  apu::Rng rng(apu::case_seed(0xC0FE, index));
  o.mul_percent = rng.below(101);
  o.add_percent = rng.below(101);
  o.func_percent = rng.below(101);
  o.mem_percent = rng.below(101);
  o.int_percent = rng.below(101);
  o.hazard_percent = rng.below(101);
  profile_ = "drawn";
  return o;
}

}  // namespace mc1::cov
