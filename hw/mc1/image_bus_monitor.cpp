#include "image_bus_monitor.hpp"

#include <algorithm>

#include "nc_extension.hpp"
#include "sc_time_conv.hpp"

namespace mc1 {

ImageBusMonitor::ImageBusMonitor(sc_core::sc_module_name name, const TimingParams& t)
    : sc_module(name), bus2dc("bus2dc"), mon2dc("mon2dc"), t_(t), grant_("image_bus_grant"),
      owner_("image_bus_owner") {
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
  mon2dc->b_transport(p, delay);
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
