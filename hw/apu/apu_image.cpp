// The APU program image (docs/apu-asm.md, "Output"): what the assembler
// writes and the MPU firmware loads.
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "apu_image.hpp"

namespace mc1::apu {
namespace {

constexpr char kMagic[4] = {'A', 'P', 'U', '1'};
constexpr size_t kHeaderBytes = 8;
constexpr size_t kWordBytes = 16;

void put_le(std::string& out, std::uint64_t v, int bytes) {
  for (int k = 0; k < bytes; ++k) out += static_cast<char>((v >> (8 * k)) & 0xFF);
}

std::uint64_t get_le(const std::string& in, size_t at, int bytes) {
  std::uint64_t v = 0;
  for (int k = bytes - 1; k >= 0; --k) v = (v << 8) | static_cast<unsigned char>(in[at + static_cast<size_t>(k)]);
  return v;
}

}  // namespace

std::string image_bytes(const std::vector<Encoded>& words) {
  std::string out(kMagic, sizeof kMagic);
  put_le(out, words.size(), 4);
  for (const auto& w : words) {
    put_le(out, w.lo, 8);
    put_le(out, w.hi, 8);
  }
  return out;
}

std::vector<Encoded> parse_image(const std::string& bytes, const std::string& name) {
  if (bytes.size() < kHeaderBytes || bytes.compare(0, 4, kMagic, 4) != 0)
    throw std::runtime_error(name + ": not an APU image (no \"APU1\" header)");
  const std::uint64_t count = get_le(bytes, 4, 4);
  if (count > static_cast<std::uint64_t>(kProgramWords))
    throw std::runtime_error(name + ": image holds " + std::to_string(count) + " words, more than 1024");
  if (bytes.size() != kHeaderBytes + count * kWordBytes)
    throw std::runtime_error(name + ": image size " + std::to_string(bytes.size()) + " bytes does not match its " +
                             std::to_string(count) + " words");
  std::vector<Encoded> words(count);
  for (size_t k = 0; k < count; ++k) {
    words[k].lo = get_le(bytes, kHeaderBytes + k * kWordBytes, 8);
    words[k].hi = get_le(bytes, kHeaderBytes + k * kWordBytes + 8, 8);
  }
  return words;
}

void write_image(const std::string& path, const std::vector<Encoded>& words) {
  std::ofstream out(path, std::ios::binary);
  const std::string bytes = image_bytes(words);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw std::runtime_error(path + ": cannot write");
}

std::vector<Encoded> load_image(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot read");
  std::ostringstream ss;
  ss << in.rdbuf();
  return parse_image(ss.str(), path);
}

}  // namespace mc1::apu
