#include "image_bus.hpp"

#include <algorithm>

#include "sc_time_conv.hpp"

namespace mc1 {

ImageBus::ImageBus(sc_core::sc_module_name name, const TimingParams& t)
    : sc_module(name), nc2bus_pixels("nc2bus_pixels"), bus2dc("bus2dc"), t_(t) {
  nc2bus_pixels.register_b_transport(this, &ImageBus::b_transport);
  SC_HAS_PROCESS(ImageBus);
  SC_THREAD(arbiter);
}

void ImageBus::b_transport(int index, tlm::tlm_generic_payload& p, sc_core::sc_time& delay) {
  sc_core::wait(delay);  // the arbiter needs the true request time
  delay = sc_core::SC_ZERO_TIME;
  Request r{static_cast<unsigned>(index) + 1, sc_core::sc_time_stamp(), &p, {}};
  pending_.push_back(&r);
  request_ev_.notify(sc_core::SC_ZERO_TIME);
  sc_core::wait(r.done);
}

ImageBus::Request* ImageBus::pick(const sc_core::sc_time& decided) {
  // Round robin among the requests made by the decision instant: the first
  // NC after the last granted one, cyclically. Requests of later instants
  // wait for the next round, whatever delta cycle they arrived in.
  const unsigned n = static_cast<unsigned>(nc2bus_pixels.size());
  auto rank = [&](const Request* r) {
    return r->requested <= decided ? (r->nc + n - last_nc_ - 1) % n : n;
  };
  auto it = std::min_element(pending_.begin(), pending_.end(), [&](Request* a, Request* b) {
    return rank(a) != rank(b) ? rank(a) < rank(b) : a->requested < b->requested;
  });
  Request* r = *it;
  pending_.erase(it);
  return r;
}

void ImageBus::arbiter() {
  for (;;) {
    if (pending_.empty()) sc_core::wait(request_ev_);
    // Arbitration decides among the requests of this instant; picking after
    // the arbitration time sees all of them, in whichever delta they came.
    const sc_core::sc_time decided = sc_core::sc_time_stamp();
    sc_core::wait(to_sc_time(t_.image_bus_arbitration_ns * 1000));
    const sc_core::sc_time granted = sc_core::sc_time_stamp();
    Request* r = pick(decided);
    last_nc_ = r->nc;

    tlm::tlm_generic_payload& p = *r->payload;
    const sc_core::sc_time transfer = to_sc_time(t_.image_bus_bytes_ps(p.get_data_length()));
    sc_core::sc_time dc_time = sc_core::SC_ZERO_TIME;
    bus2dc->b_transport(p, dc_time);
    const sc_core::sc_time hold = std::max(transfer, dc_time);
    sc_core::wait(hold);

    ++stats_.runs;
    stats_.bytes += p.get_data_length();
    if (p.get_data_length() >= kRunHeaderBytes)
      stats_.pixels += (p.get_data_length() - kRunHeaderBytes) / kBytesPerPixel;
    stats_.busy += sc_core::sc_time_stamp() - decided;
    stats_.waiting += decided - r->requested;
    if (log_)
      grants_.push_back(Grant{r->nc, r->requested, granted, sc_core::sc_time_stamp(),
                              p.get_data_length()});
    r->done.notify();
  }
}

}  // namespace mc1
