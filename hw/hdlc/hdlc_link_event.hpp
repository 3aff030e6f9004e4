// The TLM side of the HDLC lines besides message bytes: the address of a
// broadcast, and what the RC's processor and its HDLC controller tell each
// other (docs/hdlc.md "Supervision"), as a generic-payload extension with
// no data:
//   on hdlc2rc      LinkDown: NC <address>'s link is down (retry limit N2 or
//                   a poll unanswered); the controller has dropped what was
//                   queued on it;
//   on rc2nc_hdlc   SuperviseOn / SuperviseOff: poll idle links from the
//                   payload's time on, or stop (the frame is over).
#pragma once

#include <tlm>

#include "hdlc_link.hpp"
#include "timing_params.hpp"

namespace mc1 {

// TLM address of a message to every NC (NC ids are 1..N).
constexpr sc_dt::uint64 kHdlcBroadcast = 0xFFFFFFFFu;

struct HdlcLinkEvent : tlm::tlm_extension<HdlcLinkEvent> {
  enum class Kind : std::uint8_t { LinkDown, SuperviseOn, SuperviseOff };
  Kind kind = Kind::LinkDown;
  hdlc::LinkDownReason reason = hdlc::LinkDownReason::RetryLimit;
  Picos declared = 0;  // LinkDown: when the controller gave the link up

  HdlcLinkEvent() = default;
  HdlcLinkEvent(Kind k, hdlc::LinkDownReason r = hdlc::LinkDownReason::RetryLimit, Picos t = 0)
      : kind(k), reason(r), declared(t) {}
  tlm::tlm_extension_base* clone() const override { return new HdlcLinkEvent(*this); }
  void copy_from(const tlm::tlm_extension_base& other) override {
    *this = static_cast<const HdlcLinkEvent&>(other);
  }
};

}  // namespace mc1
