// The MPU's side of a node computer on simulated time (mpu_activity.hpp).
#include "mpu_activity.hpp"

namespace mc1::nc {

const char* mpu_doing_name(MpuDoing d) {
  static const char* const names[kMpuDoings] = {"idle",    "compute",  "copy",     "command",
                                                "hdlc_io", "wait_rc",  "wait_bus", "bus_out",
                                                "wait_swap", "wait_halt", "done",  "dead"};
  const auto i = static_cast<unsigned>(d);
  return i < kMpuDoings ? names[i] : "?";
}

std::uint32_t MpuState::words_left(Picos t) const {
  if (doing != MpuDoing::Copy || word_ps == 0 || t < since) return doing == MpuDoing::Copy ? words : 0;
  const Picos done = (t - since) / word_ps;
  return done >= words ? 0 : words - static_cast<std::uint32_t>(done);
}

void MpuTimeline::change(const MpuState& s) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (!states_.empty() && states_.back().since >= s.since) {
    const Picos since = states_.back().since;
    states_.back() = s;  // two changes at one time: the later holds
    states_.back().since = since;
    return;
  }
  if (cursor_ > 4096 && cursor_ * 2 > states_.size()) {  // read past: drop them
    states_.erase(states_.begin(), states_.begin() + static_cast<std::ptrdiff_t>(cursor_));
    cursor_ = 0;
  }
  states_.push_back(s);
}

MpuState MpuTimeline::at(Picos t) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (states_.empty()) return MpuState{};
  if (cursor_ >= states_.size() || states_[cursor_].since > t) cursor_ = 0;
  while (cursor_ + 1 < states_.size() && states_[cursor_ + 1].since <= t) ++cursor_;
  return states_[cursor_];
}

}  // namespace mc1::nc
