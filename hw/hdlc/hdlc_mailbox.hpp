// Where a station's HDLC controller leaves received messages until its
// processor takes them. The line delivers from another process (b_transport
// of a target socket must not wait), the station's own thread takes.
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <systemc>
#include <vector>

#include "hdlc_link.hpp"
#include "sc_time_conv.hpp"
#include "timing_params.hpp"

namespace mc1 {

class HdlcMailbox {
 public:
  struct Message {
    Picos arrived = 0;   // simulated time of delivery
    unsigned from = 0;   // 0 = RC, k = NC k
    std::vector<std::uint8_t> data;
    // Not a message: the controller reports NC `from`'s link down (at the RC).
    bool link_down = false;
    hdlc::LinkDownReason reason = hdlc::LinkDownReason::RetryLimit;
    Picos declared = 0;  // when the controller gave the link up
  };

  void put(Message m) {
    q_.push_back(std::move(m));
    ev_.notify(sc_core::SC_ZERO_TIME);
  }
  bool empty() const { return q_.empty(); }
  std::size_t size() const { return q_.size(); }
  // Blocks the calling SystemC thread until a message is there.
  Message take() {
    while (q_.empty()) sc_core::wait(ev_);
    Message m = std::move(q_.front());
    q_.pop_front();
    return m;
  }
  // Same, but gives up at simulated time `deadline` (absolute): nullopt.
  std::optional<Message> take_until(Picos deadline) {
    while (q_.empty()) {
      const Picos now = to_picos(sc_core::sc_time_stamp());
      if (now >= deadline) return std::nullopt;
      sc_core::wait(to_sc_time(deadline - now), ev_);
    }
    return take();
  }

 private:
  std::deque<Message> q_;
  sc_core::sc_event ev_;
};

}  // namespace mc1
