// The frame memory (s2, fig. 1): width x height RGB8 pixels written by the DC.
//
// dc2fm: TLM read or write at byte address 3 * (y * width + x), any length
// that stays inside the memory (else TLM_ADDRESS_ERROR_RESPONSE); a write of
// n bytes costs fm_write_ns_per_pixel per started pixel. Byte enables are not
// supported. The DMI is not offered: every access is timed.
#pragma once

#include <systemc>
#include <tlm>
#include <tlm_utils/simple_target_socket.h>
#include <vector>

#include "pixel_run.hpp"
#include "timing_params.hpp"

namespace mc1 {

class FrameMemory : public sc_core::sc_module {
 public:
  tlm_utils::simple_target_socket<FrameMemory> dc2fm;

  FrameMemory(sc_core::sc_module_name name, const TimingParams& t, unsigned width,
              unsigned height, Rgb8 clear = {});
  unsigned width() const { return width_; }
  unsigned height() const { return height_; }
  Rgb8 pixel(unsigned x, unsigned y) const;
  void set_pixel(unsigned x, unsigned y, Rgb8 c);
  const std::vector<std::uint8_t>& rgb() const { return mem_; }  // rows top first
  std::uint64_t pixels_written() const { return pixels_written_; }

 private:
  void b_transport(tlm::tlm_generic_payload& p, sc_core::sc_time& delay);
  TimingParams t_;
  unsigned width_, height_;
  std::vector<std::uint8_t> mem_;
  std::uint64_t pixels_written_ = 0;
};

}  // namespace mc1
