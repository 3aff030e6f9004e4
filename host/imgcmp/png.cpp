// PNG through libpng. libpng reports an error by longjmp to the caller's
// setjmp; the functions that call setjmp (write_png_rows, read_png_header,
// set_rgb8_transforms, read_png_rows) hold only C data and call only libpng,
// so no C++ destructor is ever jumped over. The C++ around them owns the memory.
#include "png.hpp"

#include <sys/stat.h>

#include <png.h>
#include <zlib.h>

#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string_view>

#include "atomic_file.hpp"

namespace mc1::imgcmp {
namespace {

// What the libpng callbacks share with the C++ side; C data only.
struct PngIo {
  char error[256] = "";
  // write: bytes appended here
  std::vector<std::uint8_t>* out = nullptr;
  // read: from memory, or from `file`
  const std::uint8_t* data = nullptr;
  std::size_t size = 0, pos = 0;
  std::FILE* file = nullptr;
};

[[noreturn]] void on_error(png_structp png, png_const_charp message) {
  auto* io = static_cast<PngIo*>(png_get_error_ptr(png));
  std::snprintf(io->error, sizeof io->error, "%s", message);
  png_longjmp(png, 1);
}

void on_warning(png_structp, png_const_charp) {}  // ancillary trouble: the pixels are still right

void on_write(png_structp png, png_bytep data, png_size_t n) {
  auto* io = static_cast<PngIo*>(png_get_io_ptr(png));
  try {
    io->out->insert(io->out->end(), data, data + n);
  } catch (const std::bad_alloc&) {
    png_error(png, "out of memory");
  }
}

void on_flush(png_structp) {}

void on_read(png_structp png, png_bytep data, png_size_t n) {
  auto* io = static_cast<PngIo*>(png_get_io_ptr(png));
  if (io->file) {
    if (std::fread(data, 1, n, io->file) == n) return;
    png_error(png, std::ferror(io->file) ? "read error" : "the file ends early (truncated)");
  }
  if (io->size - io->pos < n) png_error(png, "the data ends early (truncated)");
  std::memcpy(data, io->data + io->pos, n);
  io->pos += n;
}

// ---- writing --------------------------------------------------------------------

// Filter None and level 6 in one IDAT, as the zlib encoder before libpng
// wrote (compress2 at level 6: window 2^15, memory level 8, default strategy).
bool write_png_rows(png_structp png, png_infop info, std::uint32_t width, std::uint32_t height,
                    const std::uint8_t* rgb, std::size_t zbuf_size) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_IHDR(png, info, width, height, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_BASE,
               PNG_FILTER_TYPE_BASE);
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_NONE);
  png_set_compression_level(png, 6);
  png_set_compression_mem_level(png, 8);
  png_set_compression_window_bits(png, 15);
  png_set_compression_strategy(png, Z_DEFAULT_STRATEGY);
  png_set_compression_buffer_size(png, zbuf_size);  // one buffer, so one IDAT
  png_write_info(png, info);
  const std::size_t row = 3 * static_cast<std::size_t>(width);
  for (std::uint32_t y = 0; y < height; ++y) png_write_row(png, rgb + y * row);
  png_write_end(png, nullptr);
  return true;
}

// ---- reading ----------------------------------------------------------------------

bool read_png_header(png_structp png, png_infop info) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_read_info(png, info);
  return true;
}

// Grey, palette, 16-bit, alpha and interlace become 8-bit RGB rows.
bool set_rgb8_transforms(png_structp png, png_infop info) {
  if (setjmp(png_jmpbuf(png))) return false;
  const int colour = png_get_color_type(png, info);
  if (colour == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (colour == PNG_COLOR_TYPE_GRAY && png_get_bit_depth(png, info) < 8) png_set_expand_gray_1_2_4_to_8(png);
  if (png_get_bit_depth(png, info) == 16) png_set_scale_16(png);
  if ((colour & PNG_COLOR_MASK_ALPHA) || png_get_valid(png, info, PNG_INFO_tRNS)) png_set_strip_alpha(png);
  if (!(colour & PNG_COLOR_MASK_COLOR)) png_set_gray_to_rgb(png);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  return true;
}

bool read_png_rows(png_structp png, png_infop info, png_bytepp rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_read_image(png, rows);
  png_read_end(png, info);
  return true;
}

struct ReadStruct {
  png_structp png = nullptr;
  png_infop info = nullptr;
  ~ReadStruct() { png_destroy_read_struct(&png, info ? &info : nullptr, nullptr); }
};

std::string size_text(std::uint64_t w, std::uint64_t h) { return std::to_string(w) + "x" + std::to_string(h); }

Image decode(PngIo& io, const std::string& name) {
  auto bad = [&](const std::string& what) { return ImageError(name + ": " + what); };
  ReadStruct r;
  r.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &io, on_error, on_warning);
  if (r.png) r.info = png_create_info_struct(r.png);
  if (!r.info) throw bad("out of memory");
  png_set_read_fn(r.png, &io, on_read);
  if (!read_png_header(r.png, r.info)) throw bad(io.error);
  const std::uint64_t w = png_get_image_width(r.png, r.info), h = png_get_image_height(r.png, r.info);
  if (w > kMaxPngSide || h > kMaxPngSide || w * h > kMaxPngPixels)
    throw bad("the header says " + size_text(w, h) + ", over the limit of " + std::to_string(kMaxPngSide) +
              " a side and " + std::to_string(kMaxPngPixels) + " pixels");
  if (!set_rgb8_transforms(r.png, r.info)) throw bad(io.error);
  if (png_get_rowbytes(r.png, r.info) != 3 * w || png_get_channels(r.png, r.info) != 3)
    throw bad("a PNG format this reader cannot turn into 8-bit RGB");
  Image img(static_cast<int>(w), static_cast<int>(h));
  std::vector<png_bytep> rows(h);
  for (std::uint64_t y = 0; y < h; ++y) rows[y] = img.at(0, static_cast<int>(y));
  if (!read_png_rows(r.png, r.info, rows.data())) throw bad(io.error);
  return img;
}

// ---- files ------------------------------------------------------------------------

[[noreturn]] void file_error(const std::string& path, const std::string& what, int err) {
  throw ImageError(path + ": " + what + ": " + std::strerror(err));
}

}  // namespace

std::vector<std::uint8_t> encode_png_rgb8(std::uint32_t width, std::uint32_t height, const std::uint8_t* rgb) {
  if (width == 0 || height == 0 || width > kMaxPngSide || height > kMaxPngSide ||
      std::uint64_t{width} * height > kMaxPngPixels)
    throw std::invalid_argument("encode_png_rgb8: bad size " + size_text(width, height));
  PngIo io;
  std::vector<std::uint8_t> out;
  io.out = &out;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &io, on_error, on_warning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    throw std::bad_alloc();
  }
  png_set_write_fn(png, &io, on_write, on_flush);
  const uLong raw = static_cast<uLong>((3 * std::size_t{width} + 1) * height);
  const bool ok = write_png_rows(png, info, width, height, rgb, compressBound(raw) + 64);
  png_destroy_write_struct(&png, &info);
  if (!ok) throw ImageError(std::string("encode_png_rgb8: ") + io.error);
  return out;
}

std::vector<std::uint8_t> encode_png(const Image& img) {
  if (img.width <= 0 || img.height <= 0) throw std::invalid_argument("encode_png: empty image");
  return encode_png_rgb8(static_cast<std::uint32_t>(img.width), static_cast<std::uint32_t>(img.height),
                         img.rgb.data());
}

void write_file(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  write_file_atomically(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

void write_png(const std::string& path, const Image& img) { write_file(path, encode_png(img)); }

Image decode_png(const std::vector<std::uint8_t>& bytes, const std::string& name) {
  PngIo io;
  io.data = bytes.data();
  io.size = bytes.size();
  return decode(io, name);
}

Image read_png(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) file_error(path, "cannot open", errno);
  if (S_ISDIR(st.st_mode)) throw ImageError(path + ": is a directory, not a PNG file");
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), std::fclose);
  if (!f) file_error(path, "cannot open", errno);
  PngIo io;
  io.file = f.get();
  return decode(io, path);
}

}  // namespace mc1::imgcmp
