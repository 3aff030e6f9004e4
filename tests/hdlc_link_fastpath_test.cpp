// The fault-free receiver's fast path (Network::receive): a clean wire into a
// decoder at rest takes a frame whole instead of bit by bit. It must give what
// the bit-level model gives: the same wire-bit count, the same decoded frame
// and decoder state, and on a whole network the same deliveries at the same
// picoseconds, the same statistics. A wire with an inert fault (a dead window
// that is empty) is not clean, so it runs the bit-level model on the same
// traffic: the reference.
#include <gtest/gtest.h>

#include <random>

#include "hdlc_link.hpp"

using namespace mc1;
using namespace mc1::hdlc;

namespace {
constexpr Picos kUs = 1'000'000;

// Random frames, biased to what stuffing and flags care about: runs of 1s,
// flag octets, empty and long information fields.
Frame random_frame(std::mt19937_64& rng) {
  static const std::uint8_t kSpecial[] = {0xFF, 0x7E, 0x3F, 0xFC, 0x1F, 0xF8, 0x00};
  Frame f;
  f.address = static_cast<std::uint8_t>(rng());
  f.control = static_cast<std::uint8_t>(rng());
  const std::size_t len = rng() % 4 == 0 ? 0 : rng() % 300;
  for (std::size_t i = 0; i < len; ++i)
    f.info.push_back(rng() % 3 == 0 ? kSpecial[rng() % 7] : static_cast<std::uint8_t>(rng()));
  return f;
}

Bytes random_message(std::mt19937_64& rng) {
  Bytes b(rng() % 3 == 0 ? rng() % 8 : rng() % 900);
  for (std::uint8_t& x : b) x = rng() % 4 == 0 ? 0xFF : static_cast<std::uint8_t>(rng());
  return b;
}

bool operator==(const Decoder::Counters& a, const Decoder::Counters& b) {
  return a.frames_ok == b.frames_ok && a.fcs_errors == b.fcs_errors && a.aborts == b.aborts &&
         a.short_frames == b.short_frames && a.misaligned == b.misaligned;
}
}  // namespace

TEST(HdlcFastPath, WireBitsCountTheImage) {
  std::mt19937_64 rng(7);
  for (int n = 0; n < 2000; ++n) {
    const Frame f = random_frame(rng);
    ASSERT_EQ(wire_bits(f), encode(f).size()) << describe(f);
  }
  Frame ones;
  ones.address = 0xFF;
  ones.control = 0xFF;
  ones.info.assign(255, 0xFF);
  EXPECT_EQ(wire_bits(ones), encode(ones).size());
}

TEST(HdlcFastPath, TakeWholeIsWhatTheBitsDo) {
  std::mt19937_64 rng(11);
  Decoder bitwise, whole;
  for (int n = 0; n < 2000; ++n) {
    const Frame f = random_frame(rng);
    if (n % 5 == 0) {  // the line idled in between
      bitwise.idle();
      whole.idle();
    }
    ASSERT_TRUE(bitwise.at_rest());
    ASSERT_TRUE(whole.at_rest());
    std::vector<Frame> got;
    bitwise.feed(encode(f), got);
    ASSERT_EQ(got.size(), 1u) << describe(f);
    EXPECT_EQ(got[0], f) << describe(f);
    whole.take_whole();
    ASSERT_TRUE(bitwise.counters() == whole.counters());
  }
  // Both still decode the same frame the same way afterwards (same in_frame state).
  std::vector<Frame> a, b;
  const Bits tail = encode(random_frame(rng));
  bitwise.feed(tail, a);
  whole.feed(tail, b);
  EXPECT_EQ(a, b);
  EXPECT_TRUE(bitwise.counters() == whole.counters());
}

TEST(HdlcFastPath, NotCleanWithAnyFault) {
  EXPECT_TRUE(FaultyWire().clean());
  LinkFaults f;
  f.dead.push_back({0, 0});
  EXPECT_FALSE(FaultyWire(f).clean());
  LinkFaults g;
  g.flip_bits = {1u << 30};
  EXPECT_FALSE(FaultyWire(g).clean());
  LinkFaults h;
  h.bit_error_rate = 1e-9;
  EXPECT_FALSE(FaultyWire(h).clean());
}

namespace {
constexpr unsigned kNcs = 5;

struct Run {
  std::vector<Delivery> deliveries;
  std::vector<MessageStatus> status;
  std::vector<LinkDown> downs;
  Picos end = 0;
};

// Random traffic both ways and broadcasts, polls on for a while. `real`:
// faults that act (bit errors on NC 2's drop, a dead span on NC 4's upstream
// line) in both runs; `reference`: every other receiving end gets an inert
// fault, so the whole network runs bit by bit.
Run run_traffic(std::uint64_t seed, bool reference, bool real, Network& net) {
  std::mt19937_64 rng(seed);
  for (unsigned k = 1; k <= kNcs; ++k)
    for (Direction d : {Direction::Down, Direction::Up}) {
      LinkFaults f;
      if (real && k == 2 && d == Direction::Down) {
        f.bit_error_rate = 2e-4;
        f.seed = seed;
      } else if (real && k == 4 && d == Direction::Up) {
        f.dead.push_back({3'000 * kUs, 3'400 * kUs});
      } else if (reference) {
        f.dead.push_back({0, 0});
      } else {
        continue;
      }
      net.set_faults(d, k, f);
    }
  net.supervise(true, 1'000 * kUs);
  net.supervise(false, 6'000 * kUs);
  std::vector<MessageId> ids;
  Picos at = 0;
  for (int n = 0; n < 120; ++n) {
    at += rng() % 200 * kUs;
    const unsigned kind = rng() % 3;
    const unsigned k = 1 + rng() % kNcs;
    if (kind == 0)
      ids.push_back(net.send(at, 0, static_cast<std::uint8_t>(k), random_message(rng)));
    else if (kind == 1)
      ids.push_back(net.send(at, 0, kAddrBroadcast, random_message(rng)));
    else
      ids.push_back(net.send(at, k, kAddrRc, random_message(rng)));
  }
  Run r;
  // Stepped as the HDLC channel steps it, in chunks of simulated time.
  for (Picos t = 0; t < 40'000 * kUs; t += 777 * kUs) {
    net.run_until(t);
    for (Delivery& d : net.take_deliveries()) r.deliveries.push_back(std::move(d));
  }
  for (MessageId id : ids) r.status.push_back(net.status(id));
  r.downs = net.link_downs();
  r.end = net.now();
  return r;
}

void expect_same_lines(const LineStats& a, const LineStats& b, const char* what) {
  EXPECT_EQ(a.frames, b.frames) << what;
  EXPECT_EQ(a.i_frames, b.i_frames) << what;
  EXPECT_EQ(a.s_frames, b.s_frames) << what;
  EXPECT_EQ(a.info_bytes, b.info_bytes) << what;
  EXPECT_EQ(a.wire_bits, b.wire_bits) << what;
  EXPECT_EQ(a.busy_ps, b.busy_ps) << what;
  EXPECT_EQ(a.retransmissions, b.retransmissions) << what;
  EXPECT_EQ(a.poll_frames, b.poll_frames) << what;
}

void fast_equals_bitwise(std::uint64_t seed, bool real) {
  TimingParams t;
  Network fast(t, kNcs), bitwise(t, kNcs);
  const Run a = run_traffic(seed, false, real, fast);
  const Run b = run_traffic(seed, true, real, bitwise);
  ASSERT_EQ(a.deliveries.size(), b.deliveries.size());
  ASSERT_GT(a.deliveries.size(), 60u);
  for (std::size_t i = 0; i < a.deliveries.size(); ++i) {
    const Delivery& x = a.deliveries[i];
    const Delivery& y = b.deliveries[i];
    ASSERT_EQ(x.time, y.time) << "delivery " << i;
    ASSERT_EQ(x.to_station, y.to_station) << "delivery " << i;
    ASSERT_EQ(x.from_station, y.from_station) << "delivery " << i;
    ASSERT_EQ(x.address, y.address) << "delivery " << i;
    ASSERT_EQ(x.id, y.id) << "delivery " << i;
    ASSERT_EQ(x.data, y.data) << "delivery " << i;
  }
  ASSERT_EQ(a.status.size(), b.status.size());
  for (std::size_t i = 0; i < a.status.size(); ++i) {
    EXPECT_EQ(a.status[i].complete, b.status[i].complete) << "message " << i;
    EXPECT_EQ(a.status[i].completed, b.status[i].completed) << "message " << i;
    EXPECT_EQ(a.status[i].lost, b.status[i].lost) << "message " << i;
    EXPECT_EQ(a.status[i].delivered, b.status[i].delivered) << "message " << i;
  }
  ASSERT_EQ(a.downs.size(), b.downs.size());
  for (std::size_t i = 0; i < a.downs.size(); ++i) EXPECT_EQ(a.downs[i].time, b.downs[i].time);
  EXPECT_EQ(a.end, b.end);
  expect_same_lines(fast.down_line(), bitwise.down_line(), "down");
  for (unsigned k = 1; k <= kNcs; ++k) {
    expect_same_lines(fast.up_line(k), bitwise.up_line(k), "up");
    for (Direction d : {Direction::Down, Direction::Up}) {
      const ReceiveStats x = fast.receive_stats(d, k), y = bitwise.receive_stats(d, k);
      EXPECT_TRUE(x.decoder == y.decoder) << "NC " << k;
      EXPECT_EQ(x.bits_flipped, y.bits_flipped) << "NC " << k;
      EXPECT_EQ(x.bits_dead, y.bits_dead) << "NC " << k;
    }
    EXPECT_EQ(fast.sender_to_nc(k).retransmissions, bitwise.sender_to_nc(k).retransmissions);
    EXPECT_EQ(fast.sender_to_rc(k).timeouts, bitwise.sender_to_rc(k).timeouts);
    EXPECT_EQ(fast.receiver_at_nc(k).rr_sent, bitwise.receiver_at_nc(k).rr_sent);
    EXPECT_EQ(fast.supervision(k).polls, bitwise.supervision(k).polls);
    EXPECT_EQ(fast.supervision(k).poll_answers, bitwise.supervision(k).poll_answers);
  }
  if (real) {
    EXPECT_GT(fast.receive_stats(Direction::Down, 2).decoder.fcs_errors, 0u);
  }
}
}  // namespace

TEST(HdlcFastPath, NetworkFaultFreeSameAsBitLevel) {
  for (std::uint64_t seed : {1, 2, 3}) fast_equals_bitwise(seed, false);
}

TEST(HdlcFastPath, NetworkWithFaultsElsewhereSameAsBitLevel) {
  for (std::uint64_t seed : {4, 5, 6}) fast_equals_bitwise(seed, true);
}

// The line's wire time in 64 bits where the numerator fits, in 128 where
// not: the same rounded-up quotient everywhere (timing_params.cpp).
TEST(HdlcFastPath, WireTimeSameIn64And128Bits) {
  TimingParams t;
  std::mt19937_64 rng(13);
  for (std::uint64_t rate : {4'000'000ull, 3'000'001ull, 1ull, 999'999'999'989ull}) {
    t.hdlc_bit_rate_bps = rate;
    auto exact = [rate](std::uint64_t bits) {
      const unsigned __int128 num = static_cast<unsigned __int128>(bits) * 1'000'000'000'000ull;
      return static_cast<Picos>((num + rate - 1) / rate);
    };
    const std::uint64_t edge = ~std::uint64_t{0} / 1'000'000'000'000ull;  // last count that fits
    for (std::uint64_t bits : {std::uint64_t{0}, std::uint64_t{1}, std::uint64_t{88}, edge - 1, edge, edge + 1,
                               edge * 3})
      EXPECT_EQ(t.hdlc_bits_ps(bits), exact(bits)) << bits << " bits at " << rate;
    for (int n = 0; n < 1000; ++n) {
      const std::uint64_t bits = rng() % (2 * edge);
      ASSERT_EQ(t.hdlc_bits_ps(bits), exact(bits)) << bits << " bits at " << rate;
    }
  }
}
