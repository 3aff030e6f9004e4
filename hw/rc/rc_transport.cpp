#include "rc_transport.hpp"

#include "sc_time_conv.hpp"

namespace mc1::rc {

RcTransport::RcTransport(std::string owner, const TimingParams& t, unsigned nc_count,
                         tlm::tlm_initiator_socket<>& rc2nc)
    : owner_(std::move(owner)), t_(t), nc_count_(nc_count), rc2nc_(rc2nc) {}

Picos RcTransport::now() const {
  return to_picos(sc_core::sc_time_stamp()) + to_picos(qk_.get_local_time());
}

void RcTransport::work(std::uint64_t mpu_cycles) {
  const Picos ps = t_.mpu_cycles_ps(mpu_cycles);
  stats_.busy += ps;
  qk_.inc(to_sc_time(ps));
  if (qk_.need_sync()) qk_.sync();
}

void RcTransport::post(sc_dt::uint64 address, const Bytes& msg) {
  // Copy the message into the controller's buffer, then start it.
  work((msg.size() + 1) / 2 * t_.mpu_cycles_per_word_copy);
  tlm::tlm_generic_payload p;
  Bytes data = msg;
  p.set_address(address);
  p.set_data_ptr(data.data());
  p.set_data_length(static_cast<unsigned>(data.size()));
  p.set_streaming_width(static_cast<unsigned>(data.size()));
  const sc_core::sc_time taken = to_controller(p);
  if (!p.is_response_ok())
    SC_REPORT_ERROR(owner_.c_str(), ("HDLC refused a message to " + std::to_string(address) + ": " +
                                     p.get_response_string())
                                        .c_str());
  qk_.set(taken);  // the controller took the message at this local time
  ++stats_.messages_sent;
  stats_.bytes_sent += msg.size();
}

void RcTransport::supervise_links(bool on) {
  HdlcLinkEvent ev(on ? HdlcLinkEvent::Kind::SuperviseOn : HdlcLinkEvent::Kind::SuperviseOff);
  tlm::tlm_generic_payload p;
  p.set_address(kHdlcBroadcast);
  p.set_data_ptr(nullptr);
  p.set_data_length(0);
  p.set_streaming_width(0);
  p.set_extension(&ev);
  to_controller(p);  // a command, not a message: no time passes for it
  p.clear_extension(&ev);
  if (!p.is_response_ok())
    SC_REPORT_ERROR(owner_.c_str(), ("HDLC refused the supervision command: " + p.get_response_string()).c_str());
}

// A write to the controller at the processor's local time; returns that
// time as the controller annotated it.
sc_core::sc_time RcTransport::to_controller(tlm::tlm_generic_payload& p) {
  p.set_command(tlm::TLM_WRITE_COMMAND);
  p.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
  sc_core::sc_time delay = qk_.get_local_time();
  rc2nc_->b_transport(p, delay);
  return delay;
}

std::optional<HdlcMailbox::Message> RcTransport::receive(std::optional<Picos> deadline) {
  if (inbox_.empty()) qk_.sync();  // everything due up to our local time has arrived
  std::optional<HdlcMailbox::Message> m;
  if (deadline) {
    if (inbox_.empty() && now() >= *deadline) return std::nullopt;
    m = inbox_.take_until(*deadline);
    if (!m) return std::nullopt;
  } else {
    m = inbox_.take();
  }
  if (m->link_down) {  // the controller's interrupt; no message to copy
    work(t_.mpu_cycles_per_interrupt);
    return m;
  }
  receipts_.push_back({m->arrived, now(), m->from});
  ++stats_.messages_received;
  stats_.bytes_received += m->data.size();
  // Receive interrupt, then copy the message out of the controller's buffer.
  work(t_.mpu_cycles_per_interrupt + (m->data.size() + 1) / 2 * t_.mpu_cycles_per_word_copy);
  return m;
}

void RcTransport::deliver(tlm::tlm_generic_payload& p, sc_core::sc_time& delay) {
  if (p.get_command() != tlm::TLM_WRITE_COMMAND) {
    p.set_response_status(tlm::TLM_COMMAND_ERROR_RESPONSE);
    return;
  }
  const auto from = static_cast<unsigned>(p.get_address());
  if (from < 1 || from > nc_count_) {
    p.set_response_status(tlm::TLM_ADDRESS_ERROR_RESPONSE);
    return;
  }
  HdlcMailbox::Message m{to_picos(sc_core::sc_time_stamp() + delay), from,
                         Bytes(p.get_data_ptr(), p.get_data_ptr() + p.get_data_length())};
  if (const auto* ev = p.get_extension<HdlcLinkEvent>()) {
    if (ev->kind != HdlcLinkEvent::Kind::LinkDown) {
      p.set_response_status(tlm::TLM_COMMAND_ERROR_RESPONSE);
      return;
    }
    m.link_down = true;
    m.reason = ev->reason;
    m.declared = ev->declared;
  }
  inbox_.put(std::move(m));
  p.set_response_status(tlm::TLM_OK_RESPONSE);
}

}  // namespace mc1::rc
