#include "hdlc_line.hpp"

#include <string>

namespace mc1::hdlc {

HdlcLine::HdlcLine(sc_core::sc_module_name name, const TimingParams& t, unsigned nc_count)
    : sc_module(name),
      rc2nc_hdlc("rc2nc_hdlc"),
      nc2rc_hdlc("nc2rc_hdlc"),
      hdlc2nc("hdlc2nc"),
      hdlc2rc("hdlc2rc"),
      net_(t, nc_count) {
  rc2nc_hdlc.register_b_transport(this, &HdlcLine::from_rc);
  nc2rc_hdlc.register_b_transport(this, &HdlcLine::from_nc);
}

void HdlcLine::end_of_elaboration() {
  if (hdlc2nc.size() != net_.nc_count())
    SC_REPORT_ERROR(name(), ("hdlc2nc bound to " + std::to_string(hdlc2nc.size()) +
                             " NCs, the line has " + std::to_string(net_.nc_count()))
                                .c_str());
}

void HdlcLine::from_rc(tlm::tlm_generic_payload& p, sc_core::sc_time& delay) {
  carry(0, p, delay);
}

void HdlcLine::from_nc(int index, tlm::tlm_generic_payload& p, sc_core::sc_time& delay) {
  carry(static_cast<unsigned>(index) + 1, p, delay);
}

void HdlcLine::carry(unsigned from, tlm::tlm_generic_payload& p, sc_core::sc_time& delay) {
  if (p.get_command() != tlm::TLM_WRITE_COMMAND) {
    p.set_response_status(tlm::TLM_COMMAND_ERROR_RESPONSE);
    return;
  }
  if (p.get_byte_enable_ptr()) {
    p.set_response_status(tlm::TLM_BYTE_ENABLE_ERROR_RESPONSE);
    return;
  }
  const sc_dt::uint64 addr = p.get_address();
  const bool ok = from == 0 ? (addr == kAddrBroadcast || (addr >= 1 && addr <= net_.nc_count()))
                            : addr == kAddrRc;
  if (!ok) {
    p.set_response_status(tlm::TLM_ADDRESS_ERROR_RESPONSE);
    return;
  }
  const Picos stamp = to_picos(sc_core::sc_time_stamp());
  Bytes data(p.get_data_ptr(), p.get_data_ptr() + p.get_data_length());
  const MessageId id =
      net_.send(stamp + to_picos(delay), from, static_cast<std::uint8_t>(addr), std::move(data));
  const bool complete = net_.run_until_complete(id);

  for (Delivery& d : net_.take_deliveries()) {
    tlm::tlm_generic_payload q;
    q.set_command(tlm::TLM_WRITE_COMMAND);
    q.set_address(d.to_station == 0 ? d.from_station : d.address);
    q.set_data_ptr(d.data.data());
    q.set_data_length(static_cast<unsigned>(d.data.size()));
    q.set_streaming_width(static_cast<unsigned>(d.data.size()));
    q.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
    sc_core::sc_time at = to_sc_time(d.time > stamp ? d.time - stamp : 0);
    if (d.to_station == 0)
      hdlc2rc->b_transport(q, at);
    else
      hdlc2nc[static_cast<int>(d.to_station) - 1]->b_transport(q, at);
    if (q.is_response_error())
      SC_REPORT_WARNING(name(), ("station " + std::to_string(d.to_station) +
                                 " refused a message: " + q.get_response_string())
                                    .c_str());
  }
  if (!complete) {  // the link went down (retry limit N2): the message is lost
    p.set_response_status(tlm::TLM_GENERIC_ERROR_RESPONSE);
    return;
  }
  delay = to_sc_time(net_.status(id).completed - stamp);
  p.set_response_status(tlm::TLM_OK_RESPONSE);
}

}  // namespace mc1::hdlc
