// Binary images, listings and image disassembly (docs/apu-asm.md, "Output").
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "apuasm.hpp"
#include "disasm.hpp"

namespace mc1::apuasm {
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

std::string address_column(int addr) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "%04x", static_cast<unsigned>(addr));
  return buf;
}

}  // namespace

std::string image_bytes(const std::vector<apu::Encoded>& words) {
  std::string out(kMagic, sizeof kMagic);
  put_le(out, words.size(), 4);
  for (const auto& w : words) {
    put_le(out, w.lo, 8);
    put_le(out, w.hi, 8);
  }
  return out;
}

std::vector<apu::Encoded> parse_image(const std::string& bytes, const std::string& name) {
  if (bytes.size() < kHeaderBytes || bytes.compare(0, 4, kMagic, 4) != 0)
    throw std::runtime_error(name + ": not an APU image (no \"APU1\" header)");
  const std::uint64_t count = get_le(bytes, 4, 4);
  if (count > static_cast<std::uint64_t>(apu::kProgramWords))
    throw std::runtime_error(name + ": image holds " + std::to_string(count) + " words, more than 1024");
  if (bytes.size() != kHeaderBytes + count * kWordBytes)
    throw std::runtime_error(name + ": image size " + std::to_string(bytes.size()) + " bytes does not match its " +
                             std::to_string(count) + " words");
  std::vector<apu::Encoded> words(count);
  for (size_t k = 0; k < count; ++k) {
    words[k].lo = get_le(bytes, kHeaderBytes + k * kWordBytes, 8);
    words[k].hi = get_le(bytes, kHeaderBytes + k * kWordBytes + 8, 8);
  }
  return words;
}

void write_image(const std::string& path, const std::vector<apu::Encoded>& words) {
  std::ofstream out(path, std::ios::binary);
  const std::string bytes = image_bytes(words);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw std::runtime_error(path + ": cannot write");
}

std::vector<apu::Encoded> load_image(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot read");
  std::ostringstream ss;
  ss << in.rdbuf();
  return parse_image(ss.str(), path);
}

std::string readmemh_text(const std::vector<apu::Encoded>& words) {
  std::string out;
  for (const auto& w : words) {
    std::string h = apu::encoding_hex(w);
    h.erase(16, 1);  // the '_' between hi and lo
    out += h + "\n";
  }
  return out;
}

std::string listing_text(const Program& p) {
  const std::string blank(4 + 2 + 33, ' ');
  std::string out;
  for (const auto& l : p.listing) {
    if (l.addr >= 0) {
      out += address_column(l.addr) + "  " + apu::encoding_hex(p.words[static_cast<size_t>(l.addr)]) + "  ";
    } else {
      out += blank + "  ";
    }
    out += l.text + "\n";
  }
  return out;
}

std::string disassembly_text(const std::vector<apu::Encoded>& words) {
  std::string out;
  for (size_t k = 0; k < words.size(); ++k)
    out += address_column(static_cast<int>(k)) + "  " + apu::encoding_hex(words[k]) + "  " +
           apu::disassemble(words[k]) + "\n";
  return out;
}

}  // namespace mc1::apuasm
