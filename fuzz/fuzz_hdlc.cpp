// libFuzzer: the HDLC deframer (docs/hdlc.md). Three properties on every input:
//  1. any bit stream fed to the Decoder neither crashes nor hangs, and every
//     frame it delivers has a good FCS (re-encoding it decodes to itself);
//  2. round trip: a frame built from the input (address, control, info)
//     encodes to a wire image that decodes to exactly that frame;
//  3. a single wire-bit error in that image never delivers changed content:
//     every frame the decoder delivers is the one sent, or a run of bits the
//     sender itself put on the line. A flipped bit can make a flag inside the
//     frame (HDLC's flag emulation); what follows it is then framed afresh,
//     and if the information field carries a whole frame image of its own,
//     that frame is delivered (docs/hdlc.md "What the FCS cannot see"). The
//     fuzzer found such an input in its first minutes; the property says
//     precisely what CRC-16 plus zero insertion guarantee.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstdio>

#include "hdlc_frame.hpp"

using namespace mc1::hdlc;

namespace {

[[noreturn]] void violated(const char* what, const Frame& f) {
  std::fprintf(stderr, "fuzz_hdlc: %s: %s\n", what, describe(f).c_str());
  std::abort();
}

void any_stream(const std::uint8_t* data, std::size_t size) {
  Decoder d;
  std::vector<Frame> got;
  for (std::size_t i = 0; i < size; ++i)
    for (int b = 0; b < 8; ++b) d.feed_bit(static_cast<std::uint8_t>((data[i] >> b) & 1u), got);
  d.idle();
  for (const Frame& f : got) {
    std::optional<Frame> again = decode(encode(f));
    if (!again || !(*again == f)) violated("a delivered frame does not re-encode to itself", f);
  }
}

bool sent_by_sender(const Frame& got, const Bits& sent) {
  const Bits g = lsb_first_bits(frame_octets(got));
  return std::search(sent.begin(), sent.end(), g.begin(), g.end()) != sent.end();
}

void round_trip_and_one_bit_errors(const std::uint8_t* data, std::size_t size) {
  if (size < 4) return;
  Frame f;
  f.address = data[0];
  f.control = data[1];
  const std::size_t flip_seed = static_cast<std::size_t>(data[2]) | static_cast<std::size_t>(data[3]) << 8;
  f.info.assign(data + 4, data + size);
  const Bits wire = encode(f);
  std::optional<Frame> back = decode(wire);
  if (!back || !(*back == f)) violated("round trip lost the frame", f);
  const Bits sent = lsb_first_bits(frame_octets(f));
  // One flipped bit chosen by the input, and a sweep of 64 more spread over the image.
  for (std::size_t k = 0; k < 65; ++k) {
    const std::size_t bit = (flip_seed + k * (wire.size() / 64 + 1)) % wire.size();
    Bits bad = wire;
    bad[bit] ^= 1u;
    Decoder d;
    std::vector<Frame> got;
    d.feed(bad, got);
    d.idle();
    for (const Frame& g : got)
      if (!(g == f) && !sent_by_sender(g, sent)) violated("a one-bit wire error delivered changed content", g);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > 300) return 0;  // info fields on the lines are at most 256 bytes (docs/timing.md)
  any_stream(data, size);
  round_trip_and_one_bit_errors(data, size);
  return 0;
}
