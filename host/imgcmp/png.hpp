// PNG files (ISO/IEC 15948) of RGB8 images, on libpng.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "image.hpp"

namespace mc1::imgcmp {

// The largest image read or written, checked against the header before any
// pixel memory is allocated: 16384 on a side and 2^26 pixels (8192 x 8192,
// the largest frame mc1-ref writes: 192 MB of RGB). A 69-byte file claiming
// 65536 x 65536 is refused, not allocated 12.9 GB for.
constexpr std::uint32_t kMaxPngSide = 16384;
constexpr std::uint64_t kMaxPngPixels = std::uint64_t{1} << 26;

// Written: 8-bit RGB, no interlace, filter type None on every row, one IDAT
// deflated at zlib level 6 (window 2^15, memory level 8), no other chunks:
// the bytes the zlib encoder before it (hw/fm/png_writer) wrote whenever the image data,
// (3 W + 1) H bytes, is over 16384 (every mc1 frame of 96x64 and up). Up to
// 16384 libpng writes the smallest zlib window that holds the data into the
// 2-byte zlib header (Debian builds it with PNG_WRITE_OPTIMIZE_CMF, no
// run-time switch), so that header and the IDAT CRC differ; the deflate data
// and the pixels are the same.
// encode_png_rgb8 takes `height` rows of `width` pixels (R, G, B), top row
// first, and throws std::invalid_argument for a size outside the limits.
std::vector<std::uint8_t> encode_png_rgb8(std::uint32_t width, std::uint32_t height, const std::uint8_t* rgb);
std::vector<std::uint8_t> encode_png(const Image& img);

// Replaces `path` only once every byte is written (host/common/atomic_file:
// a temporary file beside it, every write and the close checked, rename; a
// device such as /dev/null or /dev/full is written in place). Throws
// std::runtime_error naming the path; a failed write leaves nothing behind.
void write_file(const std::string& path, const std::vector<std::uint8_t>& bytes);
void write_png(const std::string& path, const Image& img);

// Read: grey, palette or RGB at any bit depth, interlaced or not, converted
// to RGB8 (16-bit samples rounded to 8, an alpha channel dropped, no gamma
// correction: the samples as stored). Throws ImageError naming the file for
// a missing, unreadable, truncated or corrupt file, a directory, or an image
// over the limits above.
Image read_png(const std::string& path);
Image decode_png(const std::vector<std::uint8_t>& bytes, const std::string& name);

}  // namespace mc1::imgcmp
