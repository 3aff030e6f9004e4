// Go-back-N HDLC links RC <-> NCs with fault injection: exact fault-free
// timing, the window, exactly-once in-order delivery under bit errors and dead
// windows, and broadcast recovery when one NC receives a frame corrupted.
#include <gtest/gtest.h>

#include <map>
#include <tuple>

#include "hdlc_link.hpp"

using namespace mc1;
using namespace mc1::hdlc;

namespace {
constexpr Picos kUs = 1'000'000;
constexpr Picos kMs = 1'000'000'000;

// Messages of varied length (0..700 bytes, so 1..3 frames) whose contents name them.
Bytes make_message(std::uint32_t n, std::uint32_t seed) {
  std::uint32_t x = n * 2654435761u ^ seed;
  x ^= x >> 13;
  const std::size_t len = (n % 10 == 9) ? 0 : x % 701;
  Bytes b(len);
  for (std::size_t i = 0; i < len; ++i) {
    x = x * 1664525u + 1013904223u;
    b[i] = static_cast<std::uint8_t>(i < 4 ? n >> (8 * i) : x >> 24);
  }
  return b;
}

// Deliveries to station `to` from station `from` over link address `addr`,
// in arrival order.
std::vector<Bytes> received(const std::vector<Delivery>& all, unsigned to, unsigned from,
                            std::uint8_t addr) {
  std::vector<Bytes> out;
  for (const Delivery& d : all)
    if (d.to_station == to && d.from_station == from && d.address == addr) out.push_back(d.data);
  return out;
}

// Exactly the sent sequence: same count, then the first difference by index.
::testing::AssertionResult same_sequence(const std::vector<Bytes>& got,
                                         const std::vector<Bytes>& sent) {
  if (got.size() != sent.size())
    return ::testing::AssertionFailure()
           << got.size() << " messages delivered, " << sent.size() << " sent";
  for (std::size_t i = 0; i < got.size(); ++i)
    if (got[i] != sent[i])
      return ::testing::AssertionFailure() << "message " << i << " differs (" << got[i].size()
                                           << " bytes, sent " << sent[i].size() << ")";
  return ::testing::AssertionSuccess();
}
}  // namespace

TEST(HdlcFaults, SeededFlipsAreDeterministicAndAtTheRate) {
  LinkFaults f;
  f.bit_error_rate = 1e-3;
  f.seed = 42;
  FaultyWire a(f), b(f);
  const Bits zeros(1'000'000, 0);
  const Bits ra = a.receive(zeros, 0, 4'000'000);
  EXPECT_EQ(ra, b.receive(zeros, 0, 4'000'000));
  // 1000 expected; a Poisson count lies within +-5 sigma (158).
  EXPECT_GT(a.bits_flipped(), 842u);
  EXPECT_LT(a.bits_flipped(), 1158u);
  f.seed = 43;
  FaultyWire c(f);
  EXPECT_NE(ra, c.receive(zeros, 0, 4'000'000));
}

TEST(HdlcFaults, DeadWindowMarksAndFlipBitsAreExact) {
  LinkFaults f;
  f.dead.push_back({1 * kUs, 2 * kUs});  // bits 4..7 at 4 Mbps (250 ns each)
  f.flip_bits = {1, 12};
  FaultyWire w(f);
  const Bits got = w.receive(Bits(16, 0), 0, 4'000'000);
  EXPECT_EQ(got, (Bits{0, 1, 0, 0, 1, 1, 1, 1, 0, 0, 0, 0, 1, 0, 0, 0}));
  EXPECT_EQ(w.bits_dead(), 4u);
  EXPECT_EQ(w.bits_flipped(), 2u);
}

TEST(HdlcLink, FaultFreeMessageTimingIsExact) {
  TimingParams t;  // 4 Mbps, turnaround 10 us
  Network net(t, 3);
  const MessageId id = net.send(0, 0, 3, Bytes{'M', 'C', '-', '1'});
  ASSERT_TRUE(net.run_until_complete(id));
  // I-frame 03 00 | 01 'M' 'C' '-' '1' | E831: 88 wire bits = 22 us (see
  // hdlc_frame_test). NC 3 answers 10 us later with RR N(R)=1, address 00:
  // 00 21 CC 3F, one zero inserted after 3F's five 1s: 49 bits = 12.25 us.
  const MessageStatus& s = net.status(id);
  ASSERT_EQ(s.delivered.size(), 1u);
  EXPECT_EQ(s.delivered[0], 22 * kUs);
  EXPECT_EQ(s.completed, 22 * kUs + 10 * kUs + 12'250'000);
  const auto d = net.take_deliveries();
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].to_station, 3u);
  EXPECT_EQ(d[0].data, (Bytes{'M', 'C', '-', '1'}));
  EXPECT_EQ(net.down_line().frames, 1u);
  EXPECT_EQ(net.down_line().wire_bits, 88u);
  EXPECT_EQ(net.down_line().busy_ps, 22 * kUs);
  EXPECT_EQ(net.down_line().info_bytes, 5u);
  EXPECT_EQ(net.up_line(3).wire_bits, 49u);
  EXPECT_EQ(net.up_line(3).s_frames, 1u);
  EXPECT_EQ(net.up_line(1).frames, 0u);
  EXPECT_EQ(net.receiver_at_nc(3).rr_sent, 1u);
}

TEST(HdlcLink, WindowOfSevenFramesOutstanding) {
  TimingParams t;
  t.hdlc_turnaround_ns = 3'000'000;  // acks held back 3 ms
  t.hdlc_t1_timeout_ns = 20'000'000;
  Network net(t, 1);
  std::vector<std::pair<Picos, unsigned>> trace;  // frame starts: (time, line)
  net.set_trace([&](Picos at, unsigned line, const Frame&) { trace.emplace_back(at, line); });
  // 12 full frames back to back.
  const MessageId id = net.send(0, 0, 1, Bytes(12 * (t.hdlc_max_info_bytes - 1), 0x55));
  ASSERT_TRUE(net.run_until_complete(id));
  std::size_t before_first_ack = 0;
  for (const auto& [at, line] : trace) {
    if (line == 1) break;
    ++before_first_ack;
  }
  EXPECT_EQ(before_first_ack, 7u);
  EXPECT_EQ(net.sender_to_nc(1).i_frames, 12u);
  EXPECT_EQ(net.sender_to_nc(1).retransmissions, 0u);
}

namespace {
struct Sweep {
  double ber;
  std::uint64_t seed;
};

// Two NCs; RC -> NC and NC -> RC streams at the same time over faulty lines.
void exactly_once_both_ways(double ber, std::uint64_t seed, const std::vector<DeadWindow>& dead) {
  TimingParams t;
  Network net(t, 2);
  for (unsigned k = 1; k <= 2; ++k) {
    for (Direction d : {Direction::Down, Direction::Up}) {
      LinkFaults f;
      f.bit_error_rate = ber;
      f.seed = seed * 10 + k * 2 + (d == Direction::Up);
      if (k == 1) f.dead = dead;
      net.set_faults(d, k, f);
    }
  }
  constexpr std::uint32_t kMessages = 120;
  std::map<unsigned, std::vector<Bytes>> down, up;
  for (std::uint32_t n = 0; n < kMessages; ++n) {
    const unsigned k = 1 + n % 2;
    const Picos at = n * 300 * kUs;  // arrivals overlap the transfers
    down[k].push_back(make_message(n, 1));
    net.send(at, 0, static_cast<std::uint8_t>(k), down[k].back());
    up[k].push_back(make_message(n, 2));
    net.send(at + 7 * kUs, k, kAddrRc, up[k].back());
  }
  ASSERT_TRUE(net.run_until_all_complete(10'000 * kMs));
  const auto all = net.take_deliveries();
  std::uint64_t fcs = 0, retx = 0;
  for (unsigned k = 1; k <= 2; ++k) {
    EXPECT_TRUE(same_sequence(received(all, k, 0, static_cast<std::uint8_t>(k)), down[k]))
        << "RC -> NC " << k;
    EXPECT_TRUE(same_sequence(received(all, 0, k, kAddrRc), up[k])) << "NC " << k << " -> RC";
    fcs += net.receive_stats(Direction::Down, k).decoder.fcs_errors +
           net.receive_stats(Direction::Up, k).decoder.fcs_errors;
    retx += net.sender_to_nc(k).retransmissions + net.sender_to_rc(k).retransmissions;
  }
  EXPECT_EQ(all.size(), 4u * kMessages / 2);
  if (ber > 0) {
    EXPECT_GT(fcs, 0u);
    EXPECT_GT(retx, 0u);
  }
  if (!dead.empty()) {
    EXPECT_GT(net.receive_stats(Direction::Down, 1).bits_dead, 0u);
    EXPECT_GT(net.sender_to_nc(1).timeouts + net.sender_to_rc(1).timeouts, 0u);
    EXPECT_GT(net.sender_to_nc(1).retransmissions, 0u);
  }
  // The lines were never busy longer than the simulated time.
  EXPECT_LE(net.down_line().busy_ps, net.now());
}
}  // namespace

TEST(HdlcLink, ExactlyOnceInOrderAtBer1e5) { exactly_once_both_ways(1e-5, 1, {}); }
TEST(HdlcLink, ExactlyOnceInOrderAtBer1e4) { exactly_once_both_ways(1e-4, 2, {}); }
TEST(HdlcLink, ExactlyOnceInOrderAcrossDeadWindows) {
  exactly_once_both_ways(0.0, 3, {{2 * kMs, 9 * kMs}, {20 * kMs, 20 * kMs + 400 * kUs}});
}
TEST(HdlcLink, ExactlyOnceAtBer1e4WithDeadWindow) {
  exactly_once_both_ways(1e-4, 4, {{5 * kMs, 15 * kMs}});
}

TEST(HdlcBroadcast, OneNcReceivesAFrameCorrupted) {
  TimingParams t;
  Network net(t, 4);
  // A 3-frame broadcast: frame 0 is 8 + 8 + 8 * 256 + 16 + 8 = 2088 bits plus
  // inserted zeros (the 0x00 payload has none in the data). Flip a bit inside
  // frame 1 as NC 3 receives it.
  const std::size_t chunk = t.hdlc_max_info_bytes - 1;
  const Bytes program(3 * chunk, 0x00);
  LinkFaults f;
  f.flip_bits = {2100 + 500};
  net.set_faults(Direction::Down, 3, f);
  const MessageId id = net.send(0, 0, kAddrBroadcast, program);
  ASSERT_TRUE(net.run_until_complete(id));
  const auto all = net.take_deliveries();
  for (unsigned k = 1; k <= 4; ++k) {
    const auto got = received(all, k, 0, kAddrBroadcast);
    ASSERT_EQ(got.size(), 1u) << "NC " << k;
    EXPECT_EQ(got[0], program);
    EXPECT_EQ(net.receive_stats(Direction::Down, k).decoder.fcs_errors, k == 3 ? 1u : 0u);
    EXPECT_EQ(net.broadcast_receiver_at_nc(k).accepted, 3u);
  }
  // NC 3 saw frame 2 out of sequence and sent one REJ; the RC went back to
  // frame 1 and broadcast frames 1 and 2 again. The other NCs drop the
  // duplicates; each answers its first out-of-sequence frame with REJ N(R)=3
  // too (modulo 8 a duplicate looks like a gap), which asks for nothing.
  for (unsigned k = 1; k <= 4; ++k) EXPECT_EQ(net.broadcast_receiver_at_nc(k).rej_sent, 1u);
  EXPECT_EQ(net.sender_broadcast().rej_received, 4u);
  EXPECT_EQ(net.sender_broadcast().retransmissions, 2u);
  EXPECT_EQ(net.sender_broadcast().i_frames, 5u);
  EXPECT_EQ(net.sender_broadcast().timeouts, 0u);
  EXPECT_EQ(net.broadcast_receiver_at_nc(1).out_of_sequence, 2u);
  // NC 3 got the message last, after the others.
  const MessageStatus& s = net.status(id);
  EXPECT_GT(s.delivered[2], s.delivered[0]);
  EXPECT_EQ(s.delivered[0], s.delivered[1]);
  EXPECT_EQ(s.delivered[0], s.delivered[3]);
  EXPECT_GE(s.completed, s.delivered[2]);
}

TEST(HdlcBroadcast, ExactlyOnceWithErrorsAndOneDeadNc) {
  TimingParams t;
  Network net(t, 5);
  for (unsigned k = 1; k <= 5; ++k) {
    LinkFaults down, up;
    down.bit_error_rate = 1e-4;
    down.seed = 100 + k;
    up.bit_error_rate = 1e-5;
    up.seed = 200 + k;
    if (k == 4) down.dead.push_back({3 * kMs, 30 * kMs});
    net.set_faults(Direction::Down, k, down);
    net.set_faults(Direction::Up, k, up);
  }
  std::vector<Bytes> sent;
  for (std::uint32_t n = 0; n < 40; ++n) {
    sent.push_back(make_message(n, 7));
    net.send(n * 500 * kUs, 0, kAddrBroadcast, sent.back());
  }
  ASSERT_TRUE(net.run_until_all_complete(100'000 * kMs));
  const auto all = net.take_deliveries();
  for (unsigned k = 1; k <= 5; ++k)
    EXPECT_TRUE(same_sequence(received(all, k, 0, kAddrBroadcast), sent)) << "NC " << k;
  EXPECT_GT(net.sender_broadcast().retransmissions, 0u);
  EXPECT_GT(net.sender_broadcast().timeouts, 0u);
  EXPECT_GT(net.receive_stats(Direction::Down, 4).bits_dead, 0u);
  // One transmission serves every NC: the downstream line carried each frame
  // once plus retransmissions, not five times.
  std::size_t frames = 0;
  for (const Bytes& m : sent) frames += m.empty() ? 1 : (m.size() + 254) / 255;
  EXPECT_EQ(net.sender_broadcast().i_frames, frames + net.sender_broadcast().retransmissions);
}

TEST(HdlcLink, RejectsBadAddresses) {
  TimingParams t;
  Network net(t, 2);
  EXPECT_THROW(net.send(0, 0, 3, {}), std::invalid_argument);
  EXPECT_THROW(net.send(0, 1, 2, {}), std::invalid_argument);
  EXPECT_THROW(net.send(0, 0, kAddrRc, {}), std::invalid_argument);
}

// An N(R) one past what the sender has put on the line lies outside the
// window (docs/hdlc.md "Go-back-N": ignored if it points outside what was
// sent). Taken as an acknowledgement, it would drop a frame never sent from
// the window: the message would stall or arrive short. No conforming peer
// sends one, so NC 1's first RR is forged on the wire: the flipped bits turn
// RR N(R)=1 into RR N(R)=(frames sent)+1 with a valid FCS. It must change
// nothing: the message arrives whole, once, with no retransmission.
TEST(HdlcLink, AckOnePastWhatWasSentIsIgnored) {
  TimingParams t;
  const Bytes data(12 * (t.hdlc_max_info_bytes - 1), 0x55);  // 12 full frames
  // A clean run: NC 1's first RR, and how many I-frames had started when it ended.
  Frame ack;
  Picos ack_end = 0;
  std::uint8_t sent = 0;
  {
    Network net(t, 1);
    std::vector<std::tuple<Picos, unsigned, Frame>> trace;
    net.set_trace([&](Picos at, unsigned line, const Frame& f) { trace.emplace_back(at, line, f); });
    ASSERT_TRUE(net.run_until_complete(net.send(0, 0, 1, data)));
    for (const auto& [at, line, f] : trace)
      if (line == 1) {
        ack = f;
        ack_end = at + wire_time_ps(f, t.hdlc_bit_rate_bps);
        break;
      }
    for (const auto& [at, line, f] : trace) sent += line == 0 && at < ack_end;
  }
  ASSERT_EQ(ack.control, Control::super(Supervisory::RR, 1).octet());
  ASSERT_EQ(sent, 2u);  // frame 1 is on the line; N(R) 0..2 are in the window
  Frame forged = ack;
  forged.control = Control::super(Supervisory::RR, static_cast<std::uint8_t>(sent + 1)).octet();
  const Bits a = encode(ack), b = encode(forged);
  ASSERT_EQ(a.size(), b.size());
  LinkFaults f;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i] != b[i]) f.flip_bits.push_back(i);  // NC 1's first frame is bits 0..
  ASSERT_FALSE(f.flip_bits.empty());

  Network net(t, 1);
  net.set_faults(Direction::Up, 1, f);
  const MessageId id = net.send(0, 0, 1, data);
  ASSERT_TRUE(net.run_until_complete(id, 1000 * kMs));
  EXPECT_EQ(net.receive_stats(Direction::Up, 1).bits_flipped, f.flip_bits.size());
  EXPECT_EQ(net.receive_stats(Direction::Up, 1).decoder.fcs_errors, 0u);  // taken as good
  const auto d = net.take_deliveries();
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].data, data);
  EXPECT_EQ(net.sender_to_nc(1).i_frames, 12u);
  EXPECT_EQ(net.sender_to_nc(1).retransmissions, 0u);
  EXPECT_EQ(net.receiver_at_nc(1).accepted, 12u);
  EXPECT_TRUE(net.link_up(1));
}

// ---------------------------------------------------------------- supervision

// A silent station (its processor stopped) with a frame outstanding: T1
// expires, the RC retries N2 times, and at the next expiry gives the link
// up: the message is lost, the other NC's link is untouched.
TEST(HdlcSupervision, SilentStationIsDownAfterN2Retries) {
  TimingParams t;
  Network net(t, 2);
  net.silence(2, 1 * kMs);
  const MessageId lost = net.send(2 * kMs, 0, 2, Bytes{0xAB});
  EXPECT_FALSE(net.run_until_complete(lost, 1000 * kMs));
  EXPECT_TRUE(net.status(lost).lost);
  EXPECT_FALSE(net.status(lost).complete);
  // Every try is the same 2-octet I-frame on an idle line: the link goes
  // down N2 + 1 periods of (frame + T1) after the first one started.
  Frame f;
  f.address = 2;
  f.control = Control::info(0, 0).octet();
  f.info = {1, 0xAB};
  const Picos frame = wire_time_ps(f, t.hdlc_bit_rate_bps);
  const Picos t1 = t.hdlc_t1_timeout_ns * 1000;
  ASSERT_EQ(net.link_downs().size(), 1u);
  const LinkDown& d = net.link_downs()[0];
  EXPECT_EQ(d.nc, 2u);
  EXPECT_EQ(d.reason, LinkDownReason::RetryLimit);
  EXPECT_EQ(d.time, 2 * kMs + (t.hdlc_n2_retries + 1) * (frame + t1));
  EXPECT_EQ(net.sender_to_nc(2).retransmissions, t.hdlc_n2_retries);
  EXPECT_EQ(net.sender_to_nc(2).timeouts, t.hdlc_n2_retries + 1);
  EXPECT_EQ(net.supervision(2).max_retries, t.hdlc_n2_retries);
  EXPECT_EQ(net.receiver_at_nc(2).accepted, 0u);  // a silent station takes nothing
  EXPECT_EQ(net.up_line(2).frames, 0u);           // and answers nothing
  EXPECT_FALSE(net.link_up(2));
  EXPECT_TRUE(net.link_up(1));
  // Down for good: a later message to NC 2 is dropped at once; NC 1 works.
  const MessageId later = net.send(net.now(), 0, 2, Bytes{1});
  const MessageId fine = net.send(net.now(), 0, 1, Bytes{2});
  EXPECT_TRUE(net.run_until_complete(fine));
  EXPECT_TRUE(net.status(later).lost);
  EXPECT_EQ(net.take_link_downs().size(), 1u);
  EXPECT_TRUE(net.take_link_downs().empty());
}

// A silent NC holds the broadcast window only until its link goes down;
// then the others get the rest of the broadcast.
TEST(HdlcSupervision, BroadcastGoesOnWithoutASilentNc) {
  TimingParams t;
  Network net(t, 3);
  net.silence(2, 0);
  const Bytes program(20 * (t.hdlc_max_info_bytes - 1), 0x5A);  // 20 frames: three windows
  const MessageId id = net.send(0, 0, kAddrBroadcast, program);
  ASSERT_TRUE(net.run_until_complete(id, 1000 * kMs));
  ASSERT_EQ(net.link_downs().size(), 1u);
  EXPECT_EQ(net.link_downs()[0].nc, 2u);
  EXPECT_EQ(net.link_downs()[0].reason, LinkDownReason::RetryLimit);
  const auto all = net.take_deliveries();
  for (unsigned k : {1u, 3u}) EXPECT_EQ(received(all, k, 0, kAddrBroadcast), std::vector<Bytes>{program}) << k;
  EXPECT_TRUE(received(all, 2, 0, kAddrBroadcast).empty());
  EXPECT_GT(net.status(id).completed, net.link_downs()[0].time);
  EXPECT_EQ(net.sender_broadcast().timeouts, t.hdlc_n2_retries + 1);
}

// An idle link: nothing outstanding, so only the poll can find the silent
// station. Before it falls silent every poll is answered (RR F = 1); after,
// the RC polls N2 + 1 times, T1 apart, and gives the link up.
TEST(HdlcSupervision, PollFindsASilentStationOnAnIdleLink) {
  TimingParams t;
  Network net(t, 3);
  std::vector<std::pair<Picos, Frame>> polls_to_3;
  net.set_trace([&](Picos at, unsigned line, const Frame& f) {
    if (line == 0 && f.address == 3 && Control::parse(f.control)->pf) polls_to_3.emplace_back(at, f);
  });
  const Picos kill = 250 * kMs, interval = t.hdlc_poll_interval_ns * 1000, t1 = t.hdlc_t1_timeout_ns * 1000;
  net.supervise(true, 0);
  net.silence(3, kill);
  net.run_until(1000 * kMs);
  ASSERT_EQ(net.link_downs().size(), 1u);
  const LinkDown& d = net.link_downs()[0];
  EXPECT_EQ(d.nc, 3u);
  EXPECT_EQ(d.reason, LinkDownReason::PollUnanswered);
  // Polled at 100 and 200 ms (answered), then the first unanswered poll one
  // interval after the last answer, its N2 repeats T1 after each other.
  std::vector<Picos> after;
  for (const auto& [at, f] : polls_to_3)
    if (at > kill) after.push_back(at);
  ASSERT_EQ(after.size(), t.hdlc_n2_retries + 1);
  EXPECT_EQ(polls_to_3.size(), 2 + after.size());
  EXPECT_GE(polls_to_3[0].first, interval);
  EXPECT_LT(polls_to_3[0].first, interval + 100 * kUs);
  EXPECT_LT(after[0], kill + interval);
  const Picos poll = wire_time_ps(polls_to_3[0].second, t.hdlc_bit_rate_bps);
  for (std::size_t i = 1; i < after.size(); ++i) EXPECT_EQ(after[i] - after[i - 1], poll + t1) << i;
  EXPECT_EQ(d.time, after.back() + poll + t1);
  EXPECT_LE(d.time, kill + interval + (t.hdlc_n2_retries + 1) * (poll + t1));
  EXPECT_EQ(net.supervision(3).polls, 2 + after.size());
  EXPECT_EQ(net.supervision(3).poll_answers, 2u);
  // The live NCs were polled every interval and answered every time; polls
  // and answers cost line time like any frame.
  for (unsigned k : {1u, 2u}) {
    EXPECT_TRUE(net.link_up(k));
    EXPECT_EQ(net.supervision(k).polls, 9u) << k;  // at 100, 200, ..., 900 ms
    EXPECT_EQ(net.supervision(k).poll_answers, 9u) << k;
    EXPECT_EQ(net.up_line(k).poll_frames, 9u) << k;
    EXPECT_EQ(net.up_line(k).s_frames, 9u) << k;
  }
  EXPECT_EQ(net.down_line().poll_frames, 18 + polls_to_3.size());
  EXPECT_EQ(net.down_line().s_frames, net.down_line().poll_frames);
  EXPECT_GE(net.down_line().busy_ps, net.down_line().poll_frames * poll);
  // Off: no more polls.
  net.supervise(false, net.now());
  const std::uint64_t sent = net.down_line().frames;
  net.run_until(2000 * kMs);
  EXPECT_EQ(net.down_line().frames, sent);
}

// The defaults never take a working link down at BER 1e-4: a long exchange
// both ways, with idle gaps longer than the poll interval so that polls
// meet bit errors too, over several seeds: every message arrives exactly
// once, in order, and the retry count stays well below N2.
TEST(HdlcSupervision, NoFalseLinkDownAtBer1e4) {
  TimingParams t;
  for (std::uint64_t seed : {11u, 12u, 13u, 14u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    Network net(t, 2);
    for (unsigned k = 1; k <= 2; ++k)
      for (Direction d : {Direction::Down, Direction::Up}) {
        LinkFaults f;
        f.bit_error_rate = 1e-4;
        f.seed = seed * 10 + k * 2 + (d == Direction::Up);
        net.set_faults(d, k, f);
      }
    net.supervise(true, 0);
    std::map<unsigned, std::vector<Bytes>> down, up;
    Picos at = 0;
    for (std::uint32_t n = 0; n < 300; ++n) {
      const unsigned k = 1 + n % 2;
      at += n % 50 == 49 ? 150 * kMs : 300 * kUs;  // now and then an idle link
      down[k].push_back(make_message(n, 5));
      net.send(at, 0, static_cast<std::uint8_t>(k), down[k].back());
      up[k].push_back(make_message(n, 6));
      net.send(at + 7 * kUs, k, kAddrRc, up[k].back());
    }
    net.run_until(at + 2000 * kMs);
    EXPECT_TRUE(net.all_complete());
    EXPECT_TRUE(net.link_downs().empty());
    const auto all = net.take_deliveries();
    std::uint64_t polls = 0, timeouts = 0;
    for (unsigned k = 1; k <= 2; ++k) {
      EXPECT_TRUE(same_sequence(received(all, k, 0, static_cast<std::uint8_t>(k)), down[k])) << "RC -> NC " << k;
      EXPECT_TRUE(same_sequence(received(all, 0, k, kAddrRc), up[k])) << "NC " << k << " -> RC";
      EXPECT_LE(net.supervision(k).max_retries, t.hdlc_n2_retries / 2) << "NC " << k;  // margin
      EXPECT_FALSE(net.supervision(k).station_gave_up);
      polls += net.supervision(k).polls;
      timeouts += net.sender_to_nc(k).timeouts + net.sender_to_rc(k).timeouts;
    }
    EXPECT_GT(polls, 10u);
    EXPECT_GT(timeouts, 0u);  // the errors did cost retries
  }
}
