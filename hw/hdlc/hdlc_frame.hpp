// HDLC framing at the bit level (ISO 13239 as used on the MC-1 RC <-> NC lines,
// s2): flag 0x7E, address, control, information, FCS-16 (CRC-16/X.25), zero-bit
// insertion after five 1s, closing flag. Octets go on the wire LSB first; the
// FCS goes low octet first. See docs/hdlc.md.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace mc1::hdlc {

using Bits = std::vector<std::uint8_t>;  // one 0/1 value per wire bit, in wire order
using Bytes = std::vector<std::uint8_t>;

constexpr std::uint8_t kFlag = 0x7E;
constexpr std::uint8_t kAddrRc = 0x00;         // frames to the root computer
constexpr std::uint8_t kAddrBroadcast = 0xFF;  // frames to every NC
constexpr std::uint8_t kAddrNcFirst = 1;
constexpr std::uint8_t kAddrNcLast = 254;
constexpr std::size_t kMinFrameOctets = 4;  // address, control, FCS

// CRC-16/X.25: poly 0x1021 reflected (0x8408), init 0xFFFF, xorout 0xFFFF.
std::uint16_t fcs16(const std::uint8_t* data, std::size_t n);
inline std::uint16_t fcs16(const Bytes& b) { return fcs16(b.data(), b.size()); }

enum class FrameType : std::uint8_t { I, S, U };
enum class Supervisory : std::uint8_t { RR = 0, RNR = 1, REJ = 2, SREJ = 3 };
// Unnumbered commands/responses by their control octet with P/F = 0.
enum class Unnumbered : std::uint8_t {
  UI = 0x03, SNRM = 0x83, SABM = 0x2F, DISC = 0x43, UA = 0x63, DM = 0x0F, FRMR = 0x87
};

// The control field, modulo 8.
struct Control {
  FrameType type = FrameType::I;
  std::uint8_t ns = 0;  // I only
  std::uint8_t nr = 0;  // I and S
  bool pf = false;
  Supervisory s = Supervisory::RR;
  Unnumbered u = Unnumbered::UI;

  static Control info(std::uint8_t ns, std::uint8_t nr, bool pf = false);
  static Control super(Supervisory s, std::uint8_t nr, bool pf = false);
  static Control unnumbered(Unnumbered u, bool pf = false);
  std::uint8_t octet() const;
  static std::optional<Control> parse(std::uint8_t octet);  // nullopt: unknown U code
  bool operator==(const Control& o) const { return octet() == o.octet(); }
};

struct Frame {
  std::uint8_t address = 0;
  std::uint8_t control = 0;
  Bytes info;
  bool operator==(const Frame& o) const {
    return address == o.address && control == o.control && info == o.info;
  }
};

// Address, control, information and FCS octets (no flags, no stuffing).
Bytes frame_octets(const Frame& f);
// Octets to LSB-first bits, as on the wire before zero insertion.
Bits lsb_first_bits(const Bytes& octets);
// Octets to LSB-first bits, then zero insertion after every run of five 1s.
Bits stuff(const Bytes& octets);
// The complete wire image: opening flag, stuffed frame octets, closing flag.
Bits encode(const Frame& f);
// Bits of the wire image (flags included): what the line is busy for.
// Counted from the octets, no image built: encode(f).size().
std::size_t wire_bits(const Frame& f);
// Exact wire time in picoseconds at `bit_rate_bps` (rounded up to 1 ps).
std::uint64_t wire_time_ps(const Frame& f, std::uint64_t bit_rate_bps);

// Receive side: a stream decoder fed the line bit by bit. It hunts for a flag,
// removes inserted zeros, and at the closing flag checks length, octet
// alignment and FCS. Seven 1s abort a frame in progress (and an idle line,
// which is all 1s, looks like that).
class Decoder {
 public:
  struct Counters {
    std::uint64_t frames_ok = 0;
    std::uint64_t fcs_errors = 0;
    std::uint64_t aborts = 0;        // 7+ ones inside a frame
    std::uint64_t short_frames = 0;  // fewer than 4 octets between flags
    std::uint64_t misaligned = 0;    // not a whole number of octets
  };

  // Feeds bits; complete good frames are appended to `out`.
  void feed(const Bits& bits, std::vector<Frame>& out);
  void feed_bit(std::uint8_t bit, std::vector<Frame>& out);
  // The line idled (marking, all 1s) long enough to abort any frame.
  void idle();
  // Between frames: no bits held back, nothing since the last flag. Fed
  // encode(f) now, the decoder yields exactly f and is at rest again.
  bool at_rest() const { return ones_ == 0 && data_.empty(); }
  // What feed(encode(f), out) does to a decoder at rest, without the bits
  // (the fault-free receiver's fast path, Network::frame_end): counts the
  // good frame and stays at rest; the frame taken is f itself.
  void take_whole();
  const Counters& counters() const { return counters_; }

 private:
  void on_flag(std::vector<Frame>& out);
  bool in_frame_ = false;
  unsigned ones_ = 0;
  Bits data_;  // destuffed bits since the last flag
  Counters counters_;
};

// Convenience: decodes one complete wire image; nullopt unless exactly one good frame.
std::optional<Frame> decode(const Bits& wire, Decoder::Counters* counters = nullptr);

std::string describe(const Frame& f);  // "addr=03 I ns=1 nr=2 P info=5"

}  // namespace mc1::hdlc
