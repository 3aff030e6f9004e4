// Between the timing table's integer picoseconds and sc_time (exact below
// 2^53 ps, about 2.5 hours of simulated time).
#pragma once

#include <cmath>
#include <systemc>

#include "timing_params.hpp"

namespace mc1 {

inline sc_core::sc_time to_sc_time(Picos ps) {
  return sc_core::sc_time(static_cast<double>(ps), sc_core::SC_PS);
}

inline Picos to_picos(const sc_core::sc_time& t) {
  return static_cast<Picos>(std::llround(t.to_seconds() * 1e12));
}

}  // namespace mc1
