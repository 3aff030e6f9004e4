// The renderer's APU kernels (firmware/kernels/r_*.apu), assembled by the
// build and embedded in the library.
#pragma once

#include <string>
#include <vector>

#include "microword.hpp"

namespace mc1::render {

struct KernelImage {
  const char* name;  // "r_cast", ...
  const unsigned char* bytes;  // apuasm binary image (docs/apu-asm.md)
  unsigned long size;
};

const std::vector<KernelImage>& kernel_images();
// The microwords of kernel `name`; throws std::out_of_range for an unknown one.
const std::vector<apu::Encoded>& kernel_words(const std::string& name);

}  // namespace mc1::render
