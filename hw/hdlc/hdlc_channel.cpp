#include "hdlc_channel.hpp"

#include <algorithm>
#include <string>

#include "hdlc_link_event.hpp"
#include "sc_time_conv.hpp"

namespace mc1 {

HdlcChannel::HdlcChannel(sc_core::sc_module_name name, const TimingParams& t, unsigned nc_count)
    : sc_module(name),
      rc2nc_hdlc("rc2nc_hdlc"),
      nc2rc_hdlc("nc2rc_hdlc"),
      hdlc2nc("hdlc2nc"),
      hdlc2rc("hdlc2rc"),
      t_(t),
      nc_count_(nc_count),
      step_(t.tlm_quantum_ns * 1000) {
  if (nc_count < 1) throw std::invalid_argument("HdlcChannel: no NC");
  const unsigned ports = (nc_count + kNcsPerPort - 1) / kNcsPerPort;
  per_port_ = (nc_count + ports - 1) / ports;
  for (unsigned p = 0; p < ports; ++p)
    nets_.push_back(std::make_unique<hdlc::Network>(t, std::min(per_port_, nc_count - p * per_port_)));
  open_.resize(ports);
  rc2nc_hdlc.register_b_transport(this, &HdlcChannel::from_rc);
  nc2rc_hdlc.register_b_transport(this, &HdlcChannel::from_nc);
  SC_HAS_PROCESS(HdlcChannel);
  SC_THREAD(pump);
  SC_THREAD(tracer);
}

void HdlcChannel::end_of_elaboration() {
  if (hdlc2nc.size() != nc_count_ || nc2rc_hdlc.size() != nc_count_)
    SC_REPORT_ERROR(name(), ("bound to " + std::to_string(hdlc2nc.size()) + " NCs, the channel has " +
                             std::to_string(nc_count_))
                                .c_str());
}

void HdlcChannel::set_faults(hdlc::Direction d, unsigned nc, const hdlc::LinkFaults& f) {
  if (nc < 1 || nc > nc_count_) throw std::out_of_range("HdlcChannel::set_faults: no NC " + std::to_string(nc));
  nets_[port_of(nc)]->set_faults(d, address_of(nc), f);
}

void HdlcChannel::stop_station(unsigned nc, Picos from) {
  if (nc < 1 || nc > nc_count_) throw std::out_of_range("HdlcChannel::stop_station: no NC " + std::to_string(nc));
  nets_[port_of(nc)]->silence(address_of(nc), from);
}

bool HdlcChannel::check(tlm::tlm_generic_payload& p) {
  if (p.get_command() != tlm::TLM_WRITE_COMMAND) {
    p.set_response_status(tlm::TLM_COMMAND_ERROR_RESPONSE);
    return false;
  }
  if (p.get_byte_enable_ptr()) {
    p.set_response_status(tlm::TLM_BYTE_ENABLE_ERROR_RESPONSE);
    return false;
  }
  return true;
}

void HdlcChannel::queue(Picos at, unsigned from, sc_dt::uint64 address, const tlm::tlm_generic_payload& p,
                        Control control) {
  hdlc::Bytes data;
  if (p.get_data_length()) data.assign(p.get_data_ptr(), p.get_data_ptr() + p.get_data_length());
  pending_.push_back(Pending{at, from, address, pending_seq_++, std::move(data), control});
  sent_.notify(sc_core::SC_ZERO_TIME);
}

void HdlcChannel::submit() {
  // Every pending send is at or after the networks' time (senders are never
  // behind the kernel, the networks never ahead of it): nothing is late.
  std::sort(pending_.begin(), pending_.end(), [](const Pending& a, const Pending& b) {
    if (a.at != b.at) return a.at < b.at;
    if (a.from != b.from) return a.from < b.from;
    return a.seq < b.seq;
  });
  for (Pending& m : pending_) {
    if (m.control != Control::None) {
      supervising_ = m.control == Control::SuperviseOn;
      for (unsigned port = 0; port < ports(); ++port) nets_[port]->supervise(supervising_, m.at);
    } else if (m.from == 0 && m.address == kHdlcBroadcast) {
      for (unsigned port = 0; port < ports(); ++port)
        open_[port].push_back(nets_[port]->send(m.at, 0, hdlc::kAddrBroadcast, m.data));
    } else if (m.from == 0) {
      const auto nc = static_cast<unsigned>(m.address);
      open_[port_of(nc)].push_back(
          nets_[port_of(nc)]->send(m.at, 0, static_cast<std::uint8_t>(address_of(nc)), std::move(m.data)));
    } else {
      open_[port_of(m.from)].push_back(
          nets_[port_of(m.from)]->send(m.at, address_of(m.from), hdlc::kAddrRc, std::move(m.data)));
    }
  }
  pending_.clear();
}

void HdlcChannel::from_rc(tlm::tlm_generic_payload& p, sc_core::sc_time& delay) {
  if (!check(p)) return;
  if (const auto* ev = p.get_extension<HdlcLinkEvent>()) {
    if (ev->kind == HdlcLinkEvent::Kind::LinkDown) {
      p.set_response_status(tlm::TLM_COMMAND_ERROR_RESPONSE);
      return;
    }
    queue(to_picos(sc_core::sc_time_stamp() + delay), 0, kHdlcBroadcast, p,
          ev->kind == HdlcLinkEvent::Kind::SuperviseOn ? Control::SuperviseOn : Control::SuperviseOff);
    p.set_response_status(tlm::TLM_OK_RESPONSE);
    return;
  }
  const sc_dt::uint64 addr = p.get_address();
  if (addr != kHdlcBroadcast && (addr < 1 || addr > nc_count_)) {
    p.set_response_status(tlm::TLM_ADDRESS_ERROR_RESPONSE);
    return;
  }
  queue(to_picos(sc_core::sc_time_stamp() + delay), 0, addr, p);
  p.set_response_status(tlm::TLM_OK_RESPONSE);
}

void HdlcChannel::from_nc(int index, tlm::tlm_generic_payload& p, sc_core::sc_time& delay) {
  if (!check(p)) return;
  if (p.get_address() != hdlc::kAddrRc) {
    p.set_response_status(tlm::TLM_ADDRESS_ERROR_RESPONSE);
    return;
  }
  queue(to_picos(sc_core::sc_time_stamp() + delay), static_cast<unsigned>(index) + 1, 0, p);
  p.set_response_status(tlm::TLM_OK_RESPONSE);
}

// The grid point the networks next have to run to: the one after their
// earliest event (not before `now`: events left while nothing was open and
// the links unsupervised wait for the next send), while a message is open
// or the links are supervised (a poll, T1 of a poll); none: only a send
// wakes the pump.
std::optional<Picos> HdlcChannel::next_grid_point(Picos now) {
  if (drop_settled() && !supervising_) return std::nullopt;
  std::optional<Picos> next;
  for (const auto& net : nets_)
    if (const std::optional<Picos> t = net->next_event(); t && (!next || *t < *next)) next = t;
  if (!next) return std::nullopt;
  return std::max(grid_after(*next), now % step_ == 0 ? now : grid_after(now));
}

struct HdlcChannel::Due {
  unsigned to, from;  // global stations: 0 = RC, k = NC k
  hdlc::Delivery d;
  std::optional<hdlc::LinkDown> down;  // not a message: NC `from`'s link is down
};

bool HdlcChannel::drop_settled() {
  bool idle = pending_.empty();
  for (unsigned port = 0; port < ports(); ++port) {
    auto& open = open_[port];
    const hdlc::Network& net = *nets_[port];
    open.erase(std::remove_if(open.begin(), open.end(), [&](hdlc::MessageId id) { return net.settled(id); }),
               open.end());
    idle = idle && open.empty();
  }
  return idle;
}

// Every port's deliveries and link-downs before grid point `g` (the
// networks run up to g - 1: a send at g, handed in after this, is still
// ahead of them), in the one order that does not depend on the ports:
// time, receiver, sender, then message id.
void HdlcChannel::take_due(Picos g, std::vector<Due>& due) {
  due.clear();
  for (unsigned port = 0; port < ports(); ++port) {
    nets_[port]->run_until(g - 1);
    for (hdlc::Delivery& d : nets_[port]->take_deliveries()) {
      const unsigned to = d.to_station == 0 ? 0 : first_nc(port) + d.to_station - 1;
      const unsigned from = d.from_station == 0 ? 0 : first_nc(port) + d.from_station - 1;
      due.push_back({to, from, std::move(d), std::nullopt});
    }
    for (const hdlc::LinkDown& x : nets_[port]->take_link_downs()) {
      hdlc::Delivery d;
      d.time = x.time;
      due.push_back({0, first_nc(port) + x.nc - 1, std::move(d), x});
    }
  }
  std::sort(due.begin(), due.end(), [](const Due& a, const Due& b) {
    if (a.d.time != b.d.time) return a.d.time < b.d.time;
    if (a.to != b.to) return a.to < b.to;
    if (a.from != b.from) return a.from < b.from;
    if (a.down.has_value() != b.down.has_value()) return !a.down;  // its messages before its link-down
    return a.d.id < b.d.id;
  });
}

void HdlcChannel::deliver(Due& x) {
  tlm::tlm_generic_payload q;
  q.set_command(tlm::TLM_WRITE_COMMAND);
  q.set_data_ptr(x.d.data.data());
  q.set_data_length(static_cast<unsigned>(x.d.data.size()));
  q.set_streaming_width(static_cast<unsigned>(x.d.data.size()));
  q.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
  sc_core::sc_time at = sc_core::SC_ZERO_TIME;
  HdlcLinkEvent ev(HdlcLinkEvent::Kind::LinkDown);
  if (x.down) {
    ev.reason = x.down->reason;
    ev.declared = x.down->time;
    q.set_extension(&ev);
  }
  if (x.to == 0) {
    q.set_address(x.from);
    hdlc2rc->b_transport(q, at);
    if (x.down) q.clear_extension(&ev);
  } else {
    q.set_address(x.d.address == hdlc::kAddrBroadcast ? kHdlcBroadcast : x.to);
    hdlc2nc[static_cast<int>(x.to) - 1]->b_transport(q, at);
  }
  if (q.is_response_error())
    SC_REPORT_ERROR(name(), ("a station refused a message: " + q.get_response_string()).c_str());
}

// The first grid point (a multiple of the step) after t.
Picos HdlcChannel::grid_after(Picos t) const { return (t / step_ + 1) * step_; }

// The networks advance, and deliver, at the multiples of the step alone:
// a delivery at the first one after its closing flag, whenever the senders
// synchronised. A send reaches the networks when it is made (the pump
// wakes for it), before they run past its own time: they have run up to
// the grid point before the sender's kernel time, less 1 ps. The pump
// wakes only at the grid points after the networks' events (where
// something can be delivered), the same deliveries as at every grid point.
void HdlcChannel::pump() {
  std::vector<Due> due;
  for (;;) {
    submit();
    const Picos now = to_picos(sc_core::sc_time_stamp());
    const std::optional<Picos> g = next_grid_point(now);
    if (!g)
      sc_core::wait(sent_);
    else if (*g > now)
      sc_core::wait(to_sc_time(*g - now), sent_);
    if (!g || to_picos(sc_core::sc_time_stamp()) != *g) continue;  // a send came first
    submit();
    take_due(*g, due);
    for (Due& x : due) deliver(x);
  }
}

void HdlcChannel::trace(sc_core::sc_trace_file* tf) {
  tracing_ = true;
  for (unsigned port = 0; port < ports(); ++port) {
    const std::string n = "hdlc_down" + std::to_string(port);
    down_busy_.push_back(std::make_unique<sc_core::sc_signal<bool>>(n.c_str()));
    sc_core::sc_trace(tf, *down_busy_.back(), n);
  }
  for (unsigned nc = 1; nc <= nc_count_; ++nc) {
    const std::string n = "hdlc_up" + std::to_string(nc);
    up_busy_.push_back(std::make_unique<sc_core::sc_signal<bool>>(n.c_str()));
    sc_core::sc_trace(tf, *up_busy_.back(), n);
  }
  for (unsigned port = 0; port < ports(); ++port) {
    nets_[port]->set_trace([this, port](Picos start, unsigned line, const hdlc::Frame& f) {
      sc_core::sc_signal<bool>* sig =
          line == 0 ? down_busy_[port].get() : up_busy_[first_nc(port) + line - 2].get();
      const Picos end = start + hdlc::wire_time_ps(f, t_.hdlc_bit_rate_bps);
      // The pump learns of a frame up to one step after it started.
      const Picos from = std::max(start, to_picos(sc_core::sc_time_stamp()));
      changes_.push(Change{from, true, change_seq_++, sig});
      changes_.push(Change{end, false, change_seq_++, sig});
      change_ev_.notify(sc_core::SC_ZERO_TIME);
    });
  }
}

void HdlcChannel::tracer() {
  for (;;) {
    if (changes_.empty()) {
      sc_core::wait(change_ev_);
      continue;
    }
    const Picos now = to_picos(sc_core::sc_time_stamp());
    if (changes_.top().time > now) {
      sc_core::wait(to_sc_time(changes_.top().time - now), change_ev_);
      continue;
    }
    while (!changes_.empty() && changes_.top().time <= now) {
      changes_.top().sig->write(changes_.top().value);
      changes_.pop();
    }
    sc_core::wait(sc_core::SC_ZERO_TIME);
  }
}

}  // namespace mc1
