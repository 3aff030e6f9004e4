// Rides on an NC's image-bus payload: which NC sent the run, and when the bus
// granted it (filled in at the DC side, where the grant becomes visible).
#pragma once

#include <tlm>

#include "timing_params.hpp"

namespace mc1::nc {

struct NcIdExtension : tlm::tlm_extension<NcIdExtension> {
  unsigned nc = 0;
  bool granted_known = false;
  Picos granted = 0;

  tlm::tlm_extension_base* clone() const override { return new NcIdExtension(*this); }
  void copy_from(const tlm::tlm_extension_base& e) override {
    *this = static_cast<const NcIdExtension&>(e);
  }
};

}  // namespace mc1::nc
