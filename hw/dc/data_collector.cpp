#include "data_collector.hpp"

#include "sc_time_conv.hpp"

namespace mc1 {

DataCollector::DataCollector(sc_core::sc_module_name name, const TimingParams& t, unsigned width,
                             unsigned height)
    : sc_module(name), bus2dc("bus2dc"), dc2fm("dc2fm"), t_(t), width_(width), height_(height) {
  bus2dc.register_b_transport(this, &DataCollector::b_transport);
}

void DataCollector::b_transport(tlm::tlm_generic_payload& p, sc_core::sc_time& delay) {
  if (p.get_command() != tlm::TLM_WRITE_COMMAND) {
    ++stats_.rejected;
    p.set_response_status(tlm::TLM_COMMAND_ERROR_RESPONSE);
    return;
  }
  const auto run = decode_run(p.get_data_ptr(), p.get_data_length());
  if (!run) {
    ++stats_.rejected;
    p.set_response_status(tlm::TLM_GENERIC_ERROR_RESPONSE);
    return;
  }
  if (run->y >= height_ || run->x + run->pixels.size() > width_) {
    ++stats_.rejected;
    p.set_response_status(tlm::TLM_ADDRESS_ERROR_RESPONSE);
    return;
  }
  delay += to_sc_time(t_.dc_run_setup_ns * 1000);
  tlm::tlm_generic_payload w;
  w.set_command(tlm::TLM_WRITE_COMMAND);
  w.set_address(kBytesPerPixel * (static_cast<sc_dt::uint64>(run->y) * width_ + run->x));
  unsigned char* rgb = p.get_data_ptr() + kRunHeaderBytes;  // already R, G, B per pixel
  w.set_data_ptr(rgb);
  w.set_data_length(static_cast<unsigned>(kBytesPerPixel * run->pixels.size()));
  w.set_streaming_width(w.get_data_length());
  w.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
  dc2fm->b_transport(w, delay);
  p.set_response_status(w.get_response_status());
  if (w.is_response_ok()) {
    ++stats_.runs;
    stats_.pixels += run->pixels.size();
  } else {
    ++stats_.rejected;
  }
}

}  // namespace mc1
