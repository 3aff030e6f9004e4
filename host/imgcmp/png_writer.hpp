// A minimal PNG encoder (ISO/IEC 15948): 8-bit RGB, no interlace, filter 0
// on every row, one IDAT compressed with zlib; chunk CRCs with zlib's crc32.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace mc1 {

// `rgb` holds height rows of width pixels, 3 bytes each, top row first.
std::vector<std::uint8_t> encode_png_rgb8(std::uint32_t width, std::uint32_t height,
                                          const std::uint8_t* rgb);
void write_file(const std::string& path, const std::vector<std::uint8_t>& bytes);

}  // namespace mc1
