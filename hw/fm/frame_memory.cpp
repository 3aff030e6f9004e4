#include "frame_memory.hpp"

#include <cstring>
#include <stdexcept>

#include "sc_time_conv.hpp"

namespace mc1 {

FrameMemory::FrameMemory(sc_core::sc_module_name name, const TimingParams& t, unsigned width,
                         unsigned height, Rgb8 clear)
    : sc_module(name), dc2fm("dc2fm"), t_(t), width_(width), height_(height) {
  if (width == 0 || height == 0) throw std::invalid_argument("FrameMemory: empty frame");
  mem_.resize(kBytesPerPixel * width * height);
  for (std::size_t i = 0; i < mem_.size(); i += 3) {
    mem_[i] = clear.r;
    mem_[i + 1] = clear.g;
    mem_[i + 2] = clear.b;
  }
  dc2fm.register_b_transport(this, &FrameMemory::b_transport);
}

Rgb8 FrameMemory::pixel(unsigned x, unsigned y) const {
  const std::size_t i = kBytesPerPixel * (static_cast<std::size_t>(y) * width_ + x);
  if (x >= width_ || y >= height_) throw std::out_of_range("FrameMemory::pixel");
  return Rgb8{mem_[i], mem_[i + 1], mem_[i + 2]};
}

void FrameMemory::set_pixel(unsigned x, unsigned y, Rgb8 c) {
  if (x >= width_ || y >= height_) throw std::out_of_range("FrameMemory::set_pixel");
  const std::size_t i = kBytesPerPixel * (static_cast<std::size_t>(y) * width_ + x);
  mem_[i] = c.r;
  mem_[i + 1] = c.g;
  mem_[i + 2] = c.b;
}

void FrameMemory::b_transport(tlm::tlm_generic_payload& p, sc_core::sc_time& delay) {
  const sc_dt::uint64 a = p.get_address();
  const unsigned n = p.get_data_length();
  if (p.get_byte_enable_ptr()) {
    p.set_response_status(tlm::TLM_BYTE_ENABLE_ERROR_RESPONSE);
    return;
  }
  if (a > mem_.size() || n > mem_.size() - a) {
    p.set_response_status(tlm::TLM_ADDRESS_ERROR_RESPONSE);
    return;
  }
  if (p.is_write()) {
    std::memcpy(&mem_[a], p.get_data_ptr(), n);
    const std::uint64_t pixels = (n + kBytesPerPixel - 1) / kBytesPerPixel;
    pixels_written_ += pixels;
    delay += to_sc_time(pixels * t_.fm_write_ns_per_pixel * 1000);
  } else if (p.is_read()) {
    std::memcpy(p.get_data_ptr(), &mem_[a], n);
  } else {
    p.set_response_status(tlm::TLM_COMMAND_ERROR_RESPONSE);
    return;
  }
  p.set_response_status(tlm::TLM_OK_RESPONSE);
}

}  // namespace mc1
