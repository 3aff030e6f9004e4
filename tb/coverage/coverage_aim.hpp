// The random programs aimed at the bins still empty (apu-cosim
// --close-coverage): a set of generator profiles (weights, constraints),
// each aimed at a kind of bin; the next program takes the next profile, in
// turn, whose bins are not all hit (or waived) yet.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "apu_random.hpp"
#include "coverage_bins.hpp"

namespace mc1::cov {

class CoverageAim {
 public:
  CoverageAim(const apu::RandomOptions& base, std::vector<Waiver> waivers);
  // The options of the next program. With no profile left to aim, the base
  // options with the slot weights drawn from `index` (so that every case
  // still differs).
  apu::RandomOptions next(const Bins& bins, std::uint64_t index);
  const std::string& profile() const { return profile_; }  // the last one's name
  // The bins neither hit nor waived.
  std::vector<std::string> empty(const Bins& bins) const;

 private:
  apu::RandomOptions base_;
  std::vector<Waiver> waivers_;
  std::size_t turn_ = 0;
  std::string profile_;
};

}  // namespace mc1::cov
