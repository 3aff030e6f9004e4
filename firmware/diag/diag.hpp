// The MC-1 self-test frame (docs/platform.md "The diagnostic frame"): the
// NC firmware that computes it on the APU, the APU kernel it runs
// (firmware/kernels/diag.apu, embedded at build time), and the host's own
// computation of the expected image with the FP24 model.
#pragma once

#include <cstdint>
#include <vector>

#include "microword.hpp"
#include "nc_port.hpp"
#include "pixel_run.hpp"

namespace mc1::diag {

// Data-block layout of diag.apu (see its header).
constexpr std::uint16_t kCount = 0, kX0 = 1, kY = 2, kCx = 3, kCy = 4, kOut = 16;
constexpr unsigned kMaxRunPixels = 1024;  // 16 + 3 x 1024 words fit a 4096-word bank

// The assembled firmware/kernels/diag.apu.
const std::vector<apu::Encoded>& kernel();

// The NC's MPU firmware: load the broadcast program, read the set-up, then
// ask for blocks until Finish; each block is streamed through the APU one
// row per data bank (double-buffered), each row goes out as one pixel run.
void nc_main(nc::NcPort& port);

// The screen centre the pattern is drawn around.
inline std::uint16_t centre(std::uint16_t size) { return static_cast<std::uint16_t>(size / 2); }

// One pixel, computed on the host by the kernel's op sequence with the FP24
// model (hw/apu/fp24.hpp).
Rgb8 expected_pixel(std::uint16_t x, std::uint16_t y, std::uint16_t cx, std::uint16_t cy);
// The whole frame, rows top first, 3 bytes per pixel (FrameMemory::rgb()).
std::vector<std::uint8_t> expected_image(unsigned width, unsigned height);

}  // namespace mc1::diag
