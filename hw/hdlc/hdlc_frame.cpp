#include "hdlc_frame.hpp"

#include <cassert>
#include <cstdio>

namespace mc1::hdlc {


Control Control::info(std::uint8_t ns, std::uint8_t nr, bool pf) {
  Control c;
  c.type = FrameType::I;
  c.ns = ns & 7;
  c.nr = nr & 7;
  c.pf = pf;
  return c;
}
Control Control::super(Supervisory s, std::uint8_t nr, bool pf) {
  Control c;
  c.type = FrameType::S;
  c.s = s;
  c.nr = nr & 7;
  c.pf = pf;
  return c;
}
Control Control::unnumbered(Unnumbered u, bool pf) {
  Control c;
  c.type = FrameType::U;
  c.u = u;
  c.pf = pf;
  return c;
}

std::uint8_t Control::octet() const {
  const std::uint8_t p = pf ? 0x10 : 0x00;
  switch (type) {
    case FrameType::I: return static_cast<std::uint8_t>((ns & 7) << 1 | p | (nr & 7) << 5);
    case FrameType::S:
      return static_cast<std::uint8_t>(0x01 | static_cast<unsigned>(s) << 2 | p | (nr & 7) << 5);
    case FrameType::U: return static_cast<std::uint8_t>(static_cast<std::uint8_t>(u) | p);
  }
  return 0;
}

std::optional<Control> Control::parse(std::uint8_t o) {
  Control c;
  c.pf = (o & 0x10) != 0;
  if ((o & 0x01) == 0) {
    c.type = FrameType::I;
    c.ns = (o >> 1) & 7;
    c.nr = (o >> 5) & 7;
    return c;
  }
  if ((o & 0x03) == 0x01) {
    c.type = FrameType::S;
    c.s = static_cast<Supervisory>((o >> 2) & 3);
    c.nr = (o >> 5) & 7;
    return c;
  }
  c.type = FrameType::U;
  const std::uint8_t code = o & ~0x10;
  for (Unnumbered u : {Unnumbered::UI, Unnumbered::SNRM, Unnumbered::SABM, Unnumbered::DISC,
                       Unnumbered::UA, Unnumbered::DM, Unnumbered::FRMR})
    if (code == static_cast<std::uint8_t>(u)) {
      c.u = u;
      return c;
    }
  return std::nullopt;
}

Bytes frame_octets(const Frame& f) {
  Bytes o;
  o.reserve(f.info.size() + 4);
  o.push_back(f.address);
  o.push_back(f.control);
  o.insert(o.end(), f.info.begin(), f.info.end());
  const std::uint16_t fcs = fcs16(o);
  o.push_back(static_cast<std::uint8_t>(fcs & 0xFF));
  o.push_back(static_cast<std::uint8_t>(fcs >> 8));
  return o;
}

namespace {
void push_flag(Bits& b) {
  for (int i = 0; i < 8; ++i) b.push_back((kFlag >> i) & 1);
}
}  // namespace

Bits lsb_first_bits(const Bytes& octets) {
  Bits b;
  b.reserve(octets.size() * 8);
  for (std::uint8_t o : octets)
    for (int i = 0; i < 8; ++i) b.push_back(static_cast<std::uint8_t>((o >> i) & 1u));
  return b;
}

Bits stuff(const Bytes& octets) {
  Bits b;
  b.reserve(octets.size() * 8 * 6 / 5 + 8);
  unsigned ones = 0;
  for (std::uint8_t o : octets)
    for (int i = 0; i < 8; ++i) {
      const std::uint8_t bit = (o >> i) & 1;
      b.push_back(bit);
      ones = bit ? ones + 1 : 0;
      if (ones == 5) {
        b.push_back(0);
        ones = 0;
      }
    }
  return b;
}

Bits encode(const Frame& f) {
  Bits b;
  push_flag(b);
  const Bits body = stuff(frame_octets(f));
  b.insert(b.end(), body.begin(), body.end());
  push_flag(b);
  return b;
}

namespace {
// Zero insertion's count over one octet, LSB first: `ones` carries the run of 1s.
unsigned stuffed_zeros(std::uint8_t o, unsigned& ones) {
  unsigned zeros = 0;
  for (int i = 0; i < 8; ++i) {
    ones = (o >> i) & 1 ? ones + 1 : 0;
    if (ones == 5) {
      ++zeros;
      ones = 0;
    }
  }
  return zeros;
}

std::uint16_t fcs16_step(std::uint16_t crc, std::uint8_t o) {
  crc ^= o;
  for (int b = 0; b < 8; ++b) crc = (crc & 1) ? (crc >> 1) ^ 0x8408 : crc >> 1;
  return crc;
}
}  // namespace

std::uint16_t fcs16(const std::uint8_t* data, std::size_t n) {
  std::uint16_t crc = 0xFFFF;
  for (std::size_t i = 0; i < n; ++i) crc = fcs16_step(crc, data[i]);
  return crc ^ 0xFFFF;
}

std::size_t wire_bits(const Frame& f) {
  unsigned ones = 0;
  std::size_t zeros = 0;
  std::uint16_t crc = 0xFFFF;
  auto octet = [&](std::uint8_t o) {
    crc = fcs16_step(crc, o);
    zeros += stuffed_zeros(o, ones);
  };
  octet(f.address);
  octet(f.control);
  for (std::uint8_t o : f.info) octet(o);
  const std::uint16_t fcs = crc ^ 0xFFFF;
  zeros += stuffed_zeros(static_cast<std::uint8_t>(fcs & 0xFF), ones);
  zeros += stuffed_zeros(static_cast<std::uint8_t>(fcs >> 8), ones);
  return 16 + 8 * (f.info.size() + kMinFrameOctets) + zeros;
}

std::uint64_t wire_time_ps(const Frame& f, std::uint64_t bit_rate_bps) {
  const unsigned __int128 num =
      static_cast<unsigned __int128>(wire_bits(f)) * 1'000'000'000'000ULL;
  return static_cast<std::uint64_t>((num + bit_rate_bps - 1) / bit_rate_bps);
}

void Decoder::feed(const Bits& bits, std::vector<Frame>& out) {
  for (std::uint8_t b : bits) feed_bit(b, out);
}

void Decoder::feed_bit(std::uint8_t bit, std::vector<Frame>& out) {
  if (bit) {
    // Ones are held back until a 0 tells whether they were data, a flag or an abort.
    if (++ones_ == 7) {
      if (in_frame_ && !data_.empty()) ++counters_.aborts;
      in_frame_ = false;
      data_.clear();
    }
    return;
  }
  const unsigned ones = ones_;
  ones_ = 0;
  if (ones >= 7) return;  // end of an abort / idle run: still hunting
  if (ones == 6) {
    on_flag(out);
    return;
  }
  if (!in_frame_) return;
  data_.insert(data_.end(), ones, 1);
  if (ones != 5) data_.push_back(0);  // after five 1s the 0 was inserted: drop it
}

void Decoder::on_flag(std::vector<Frame>& out) {
  // The flag's leading 0 was taken as data; it is not.
  if (in_frame_ && !data_.empty()) {
    data_.pop_back();
    if (!data_.empty()) {
      if (data_.size() % 8 != 0) {
        ++counters_.misaligned;
      } else if (data_.size() < kMinFrameOctets * 8) {
        ++counters_.short_frames;
      } else {
        Bytes o(data_.size() / 8, 0);
        for (std::size_t i = 0; i < data_.size(); ++i)
          o[i / 8] |= static_cast<std::uint8_t>(data_[i] << (i % 8));
        const std::uint16_t got = static_cast<std::uint16_t>(o[o.size() - 2] | o.back() << 8);
        if (fcs16(o.data(), o.size() - 2) != got) {
          ++counters_.fcs_errors;
        } else {
          ++counters_.frames_ok;
          Frame f;
          f.address = o[0];
          f.control = o[1];
          f.info.assign(o.begin() + 2, o.end() - 2);
          out.push_back(std::move(f));
        }
      }
    }
  }
  in_frame_ = true;
  data_.clear();
}

void Decoder::take_whole() {
  assert(at_rest());
  ++counters_.frames_ok;
  in_frame_ = true;  // the closing flag opens the next frame
}

void Decoder::idle() {
  if (in_frame_ && !data_.empty()) ++counters_.aborts;
  in_frame_ = false;
  ones_ = 0;
  data_.clear();
}

std::optional<Frame> decode(const Bits& wire, Decoder::Counters* counters) {
  Decoder d;
  std::vector<Frame> out;
  d.feed(wire, out);
  if (counters) *counters = d.counters();
  if (out.size() != 1) return std::nullopt;
  return out.front();
}

std::string describe(const Frame& f) {
  char buf[96];
  const auto c = Control::parse(f.control);
  if (!c) {
    std::snprintf(buf, sizeof buf, "addr=%02X ctl=%02X info=%zu", f.address, f.control,
                  f.info.size());
  } else if (c->type == FrameType::I) {
    std::snprintf(buf, sizeof buf, "addr=%02X I ns=%u nr=%u%s info=%zu", f.address, c->ns, c->nr,
                  c->pf ? " P" : "", f.info.size());
  } else if (c->type == FrameType::S) {
    static const char* names[] = {"RR", "RNR", "REJ", "SREJ"};
    std::snprintf(buf, sizeof buf, "addr=%02X %s nr=%u%s", f.address,
                  names[static_cast<int>(c->s)], c->nr, c->pf ? " P/F" : "");
  } else {
    std::snprintf(buf, sizeof buf, "addr=%02X U %02X%s info=%zu", f.address,
                  static_cast<unsigned>(c->u), c->pf ? " P/F" : "", f.info.size());
  }
  return buf;
}

}  // namespace mc1::hdlc
