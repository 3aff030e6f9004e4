#include "image_bus_monitor.hpp"

#include <algorithm>

#include "nc_extension.hpp"
#include "sc_time_conv.hpp"

namespace mc1 {

ImageBusMonitor::ImageBusMonitor(sc_core::sc_module_name name, const TimingParams& t, unsigned width,
                                 unsigned height)
    : sc_module(name), bus2dc("bus2dc"), mon2dc("mon2dc"), t_(t), grant_("image_bus_grant"),
      owner_("image_bus_owner"), width_(width), height_(height),
      written_(static_cast<std::size_t>(width) * height, false) {
  bus2dc.register_b_transport(this, &ImageBusMonitor::b_transport);
  SC_HAS_PROCESS(ImageBusMonitor);
  SC_METHOD(release);
  sensitive << release_ev_;
  dont_initialize();
}

void ImageBusMonitor::trace(sc_core::sc_trace_file* tf) {
  sc_core::sc_trace(tf, grant_, "image_bus_grant");
  sc_core::sc_trace(tf, owner_, "image_bus_owner");
}

void ImageBusMonitor::b_transport(tlm::tlm_generic_payload& p, sc_core::sc_time& delay) {
  const sc_core::sc_time granted = sc_core::sc_time_stamp() + delay;
  nc::NcIdExtension* ext = nullptr;
  p.get_extension(ext);
  if (ext) {
    ext->granted_known = true;
    ext->granted = to_picos(granted);
  }
  const sc_core::sc_time before = delay;
  // The run's header (pixel_run.hpp): x, y, count.
  const unsigned char* d = p.get_data_ptr();
  const bool header = p.get_data_length() >= 6;
  const unsigned x = header ? d[0] | d[1] << 8 : 0, y = header ? d[2] | d[3] << 8 : 0,
                 n = header ? d[4] | d[5] << 8 : 0;
  const bool inside = header && y < height_ && x + n <= width_;
  bool duplicate = inside && n > 0;
  for (unsigned i = 0; duplicate && i < n; ++i) duplicate = written_[std::size_t{y} * width_ + x + i];
  if (duplicate) {
    ++duplicate_runs_;
    duplicate_pixels_ += n;
    p.set_response_status(tlm::TLM_OK_RESPONSE);
  } else {
    mon2dc->b_transport(p, delay);
    if (inside && p.is_response_ok())
      for (unsigned i = 0; i < n; ++i) written_[std::size_t{y} * width_ + x + i] = true;
  }
  const sc_core::sc_time transfer = to_sc_time(t_.image_bus_bytes_ps(p.get_data_length()));
  const sc_core::sc_time hold = std::max(transfer, delay - before);
  grant_.write(true);
  owner_.write(ext ? ext->nc : 0);
  release_at_ = granted + hold;
  release_ev_.notify(release_at_ - sc_core::sc_time_stamp());
}

void ImageBusMonitor::release() {
  if (sc_core::sc_time_stamp() < release_at_) return;  // a newer grant is running
  grant_.write(false);
  owner_.write(0);
}

}  // namespace mc1
