// The diag kernel image, embedded by the build (firmware/CMakeLists.txt) from
// the assembled firmware/kernels/diag.apu.
#include <string>

#include "apu_image.hpp"
#include "diag.hpp"

extern const unsigned char mc1_diag_kernel_image[];
extern const unsigned long mc1_diag_kernel_image_size;

namespace mc1::diag {

const std::vector<apu::Encoded>& kernel() {
  static const std::vector<apu::Encoded> words = apu::parse_image(
      std::string(reinterpret_cast<const char*>(mc1_diag_kernel_image), mc1_diag_kernel_image_size),
      "diag.bin (embedded)");
  return words;
}

}  // namespace mc1::diag
