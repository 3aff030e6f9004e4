// Reliable HDLC links between the RC and its NCs (s2), simulated at the bit
// level with fault injection. docs/hdlc.md describes the protocol.
//
// Topology: the RC transmits on one multidrop downstream line that every NC
// hears (so a broadcast is one transmission); each NC answers on its own
// upstream line to the RC. Logical links, each go-back-N with a window of
// hdlc_window (<= 7) and the timer T1:
//   RC -> NC k     I-frames address k on the downstream line, acks (RR/REJ)
//                  address 0 on NC k's upstream line;
//   RC -> all NCs  I-frames address 0xFF (own sequence numbers), each NC acks
//                  with RR/REJ address 0xFF on its upstream line; the RC keeps
//                  per-NC acknowledgement state and the window base is the
//                  slowest NC; a go-back retransmission is again a broadcast;
//   NC k -> RC     I-frames address 0 on the upstream line, acks address k on
//                  the downstream line.
// A message is cut into I-frames whose information field starts with one
// segment octet (bit 0 = last segment of the message).
//
// Link supervision (docs/hdlc.md "Supervision"): every T1 expiry that finds
// the far station silent since the last one counts a retry; after
// hdlc_n2_retries of them the RC declares NC k's link down. While
// supervise() is on, the RC also polls (RR with P = 1) a station it has not
// heard from for hdlc_poll_interval_ns when nothing is outstanding to it; a
// poll unanswered N2 + 1 times in a row takes the link down too. A link that
// is down stays down (no link set-up is modelled): the messages queued on
// it in either direction are dropped (MessageStatus::lost) and the NC no
// longer holds the broadcast window. A station can be stopped (silence(): its
// link protocol runs on the NC's processor): from then on it sends, answers
// and takes nothing. While a link is up, every message arrives exactly once
// and in order once the line works again.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <queue>
#include <vector>

#include "hdlc_frame.hpp"
#include "timing_params.hpp"

namespace mc1::hdlc {

constexpr Picos kNever = ~Picos{0};

struct DeadWindow {
  Picos begin = 0;  // [begin, end): bits sent in this span arrive as idle 1s
  Picos end = 0;    // kNever: the line is cut for good
};

// Faults of one receiving end of a line.
struct LinkFaults {
  double bit_error_rate = 0.0;  // independent flips, seeded, deterministic
  std::uint64_t seed = 1;
  std::vector<DeadWindow> dead;
  std::vector<std::uint64_t> flip_bits;  // absolute received-bit indices to flip
};

// Applies LinkFaults to the bits one receiver sees.
class FaultyWire {
 public:
  FaultyWire() : FaultyWire(LinkFaults{}) {}
  explicit FaultyWire(LinkFaults f);
  // Bit i of `sent` is on the wire from start + i * 1e12 / bit_rate_bps.
  Bits receive(const Bits& sent, Picos start, std::uint64_t bit_rate_bps);
  // No faults at all: receive() returns what was sent, whatever it is.
  bool clean() const { return f_.bit_error_rate <= 0.0 && f_.dead.empty() && f_.flip_bits.empty(); }
  // What receive() does to a clean wire for `bits` bits: counts them.
  void pass(std::uint64_t bits) { seen_ += bits; }
  std::uint64_t bits_flipped() const { return flipped_; }
  std::uint64_t bits_dead() const { return dead_; }

 private:
  std::uint64_t next_random();
  void draw_gap();
  LinkFaults f_;
  std::uint64_t rng_;
  std::uint64_t gap_ = 0;  // good bits before the next random flip
  std::uint64_t seen_ = 0, flipped_ = 0, dead_ = 0;
};

enum class Direction { Down, Up };  // Down: RC -> NC drop; Up: NC -> RC

struct LineStats {
  std::uint64_t frames = 0, i_frames = 0, s_frames = 0;
  std::uint64_t info_bytes = 0;  // information-field octets of I-frames
  std::uint64_t wire_bits = 0;   // flags and inserted zeros included
  Picos busy_ps = 0;
  std::uint64_t retransmissions = 0;  // I-frames sent again
  std::uint64_t poll_frames = 0;      // RR with P/F set: polls (down), their answers (up)
};

struct ReceiveStats {
  Decoder::Counters decoder;
  std::uint64_t bits_flipped = 0, bits_dead = 0;
};

struct SenderStats {
  std::uint64_t i_frames = 0, retransmissions = 0, timeouts = 0, rej_received = 0;
  std::uint64_t messages_completed = 0;
};

struct ReceiverStats {
  std::uint64_t accepted = 0, out_of_sequence = 0, messages = 0, rr_sent = 0, rej_sent = 0;
};

enum class LinkDownReason : std::uint8_t {
  RetryLimit,      // N2 retransmissions after T1 without a frame from the station
  PollUnanswered,  // an idle link's poll unanswered N2 + 1 times in a row
};
const char* link_down_reason_name(LinkDownReason r);  // "retry limit", "poll unanswered"

struct LinkDown {
  Picos time = 0;  // the RC declared it
  unsigned nc = 0;
  LinkDownReason reason = LinkDownReason::RetryLimit;
};

// The RC's supervision of one NC's link, and that station's side.
struct SupervisionStats {
  std::uint64_t polls = 0;         // polls the RC sent it
  std::uint64_t poll_answers = 0;  // RR with F = 1 heard from it
  unsigned max_retries = 0;        // most retries counted in a row on any of its links (margin to N2)
  bool station_gave_up = false;    // the NC's own sender reached N2 (it then fell silent)
};

using MessageId = std::uint64_t;

struct Delivery {
  Picos time = 0;           // closing flag of the message's last frame
  unsigned to_station = 0;  // 0 = RC, k = NC k
  unsigned from_station = 0;
  std::uint8_t address = 0;  // link address: NC id, 0xFF or 0
  MessageId id = 0;
  Bytes data;
};

struct MessageStatus {
  unsigned from_station = 0;
  std::uint8_t address = 0;
  Picos submitted = 0;  // when it entered the send queue
  bool complete = false;
  Picos completed = 0;  // the last acknowledgement (of every NC, for a broadcast)
  bool lost = false;    // dropped: its link went down (never complete)
  std::size_t frames = 0;
  std::vector<Picos> delivered;  // per destination station, in station order
};

class Network {
 public:
  Network(const TimingParams& t, unsigned nc_count);
  ~Network();
  Network(const Network&) = delete;
  Network& operator=(const Network&) = delete;

  unsigned nc_count() const { return nc_count_; }
  void set_faults(Direction d, unsigned nc, const LinkFaults& f);
  // NC `nc`'s station falls silent at `from`: a frame it is sending completes,
  // nothing more is sent, answered or taken (its processor ran the protocol).
  void silence(unsigned nc, Picos from);
  // From `at` on, the RC polls idle links (on) or stops polling (off).
  void supervise(bool on, Picos at);

  // Queues a message at time `at` (or now, if `at` is already past).
  // From the RC (station 0): address = NC id or kAddrBroadcast; from NC k: kAddrRc.
  MessageId send(Picos at, unsigned from_station, std::uint8_t address, Bytes data);

  Picos now() const { return now_; }
  void run_until(Picos t);
  // Runs until message `id` is complete or lost; true if complete, false if
  // lost or `limit` passes first. (With supervise() on, events never run out.)
  bool run_until_complete(MessageId id, Picos limit = ~Picos{0});
  // Runs until every message is complete or lost; true if every one is complete.
  bool run_until_all_complete(Picos limit = ~Picos{0});
  bool all_complete() const;
  bool settled(MessageId id) const { return messages_.at(id).complete || messages_.at(id).lost; }
  std::optional<Picos> next_event() const;  // time of the earliest scheduled event

  bool link_up(unsigned nc) const;
  std::vector<LinkDown> take_link_downs();  // declared since the last call, in order
  const std::vector<LinkDown>& link_downs() const { return link_downs_; }

  const MessageStatus& status(MessageId id) const;
  std::vector<Delivery> take_deliveries();

  const LineStats& down_line() const;
  const LineStats& up_line(unsigned nc) const;
  ReceiveStats receive_stats(Direction d, unsigned nc) const;
  const SenderStats& sender_to_nc(unsigned nc) const;
  const SenderStats& sender_broadcast() const;
  const SenderStats& sender_to_rc(unsigned nc) const;
  const ReceiverStats& receiver_at_nc(unsigned nc) const;  // RC -> NC link
  const ReceiverStats& broadcast_receiver_at_nc(unsigned nc) const;
  const SupervisionStats& supervision(unsigned nc) const;
  // Every frame put on any line, for tracing: (start time, line, frame); line 0 = down.
  void set_trace(std::function<void(Picos, unsigned, const Frame&)> fn) { trace_ = std::move(fn); }

 private:
  struct Segment;
  struct Sender;
  struct Receiver;
  struct Endpoint;
  struct Line;
  struct Station;

  void at(Picos t, std::function<void()> fn);
  // An event from outside (a send, a supervision command of station
  // `from`): at one instant before the network's own events, by station,
  // then in call order, so that the outcome does not depend on when the
  // caller handed it in (before or after the network's own events for that
  // instant were scheduled).
  void at_external(Picos t, unsigned from, std::function<void()> fn);
  void step();
  void try_transmit(Line& l);
  bool transmit_ack(Line& l, Picos& earliest);
  bool transmit_poll(Line& l);
  void transmit(Line& l, Frame f, Sender* s, unsigned poll_nc = 0);
  void frame_end(Line& l, const Frame& f, std::size_t bits, Picos start, Sender* s, unsigned poll_nc);
  void receive(Line& l, Endpoint& ep, const Frame& f, std::size_t bits, Bits& image, Picos start);
  void dispatch(Line& l, Endpoint& ep, const Frame& f);
  void on_info(Receiver& r, const Frame& f, const Control& c);
  void on_ack(Sender& s, std::size_t peer, std::uint8_t nr, bool rej);
  void advance_base(Sender& s);
  void schedule_ack(Receiver& r, Supervisory kind);
  bool sendable(const Sender& s) const;
  void start_timer(Sender& s, Picos from);
  void t1_expired(Sender& s);
  bool count_retry(unsigned& retries, unsigned nc);  // false: N2 reached
  bool silent(unsigned nc) const;
  bool outstanding_to(unsigned nc) const;
  void heard_from(unsigned nc);
  void heard_by(unsigned nc);
  void schedule_idle_check(unsigned nc, Picos t);
  void idle_check(unsigned nc);
  void poll_expired(unsigned nc, std::uint64_t gen);
  void link_down(unsigned nc, LinkDownReason why);
  void drop(Sender& s);

  TimingParams t_;
  unsigned nc_count_;
  Picos now_ = 0;
  std::uint64_t ev_seq_ = 0;
  struct Event {
    Picos t;
    std::uint64_t rank;  // external: the sending station; internal: kInternal (after every station)
    std::uint64_t seq;
    std::function<void()> fn;
    static constexpr std::uint64_t kInternal = ~std::uint64_t{0};
    bool operator>(const Event& o) const {
      if (t != o.t) return t > o.t;
      if (rank != o.rank) return rank > o.rank;
      return seq > o.seq;
    }
  };
  std::priority_queue<Event, std::vector<Event>, std::greater<Event>> events_;

  std::vector<std::unique_ptr<Line>> lines_;           // 0 = down, k = up from NC k
  std::vector<std::unique_ptr<Sender>> to_nc_, to_rc_;  // index k-1
  std::unique_ptr<Sender> broadcast_;
  std::vector<std::unique_ptr<Receiver>> at_nc_, bcast_at_nc_, at_rc_;  // index k-1
  std::vector<MessageStatus> messages_;
  std::vector<Delivery> deliveries_;
  std::vector<Station> stations_;  // index k-1
  bool supervising_ = false;
  std::size_t rr_poll_ = 0;
  std::vector<LinkDown> link_downs_;
  std::size_t link_downs_taken_ = 0;
  std::function<void(Picos, unsigned, const Frame&)> trace_;
};

}  // namespace mc1::hdlc
