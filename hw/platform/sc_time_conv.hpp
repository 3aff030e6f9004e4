// Between the timing table's integer picoseconds and sc_time. At SystemC's
// default resolution of 1 ps (the platform's), an sc_time's value is its
// picosecond count: the conversions are a copy, no floating point (they run
// several times per APU run). At another resolution they go through double,
// exact below 2^53 ps, about 2.5 hours of simulated time.
#pragma once

#include <cmath>
#include <systemc>

#include "timing_params.hpp"

namespace mc1 {
namespace detail {
// Asked once; the first sc_time with a value fixes the resolution anyway.
inline bool sc_resolution_is_ps() {
  static const bool ps = sc_core::sc_get_time_resolution() == sc_core::sc_time(1.0, sc_core::SC_PS);
  return ps;
}
}  // namespace detail

inline sc_core::sc_time to_sc_time(Picos ps) {
  if (detail::sc_resolution_is_ps()) return sc_core::sc_time::from_value(ps);
  return sc_core::sc_time(static_cast<double>(ps), sc_core::SC_PS);
}

inline Picos to_picos(const sc_core::sc_time& t) {
  if (detail::sc_resolution_is_ps()) return static_cast<Picos>(t.value());
  return static_cast<Picos>(std::llround(t.to_seconds() * 1e12));
}

}  // namespace mc1
