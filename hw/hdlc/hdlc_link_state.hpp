// The go-back-N network's private state (hdlc_link.hpp's Network): shared by
// hdlc_link.cpp (set-up, events, sending, results), hdlc_link_supervision.cpp
// and hdlc_link_receive.cpp. Not part of the interface.
#pragma once

#include <deque>
#include <utility>
#include <vector>

#include "hdlc_link.hpp"

namespace mc1::hdlc {

struct Network::Segment {
  Bytes info;
  MessageId msg;
};

struct Network::Sender {
  std::uint8_t address = 0;
  unsigned line = 0;
  unsigned from_station = 0;
  std::vector<unsigned> peers;   // stations that acknowledge
  Receiver* reverse = nullptr;   // whose V(R) rides in our I-frames as N(R)
  std::deque<Segment> frames;    // frames[0] has sequence number `base`
  std::uint64_t base = 0, next = 0, highest = 0;  // absolute sequence numbers
  std::vector<std::uint64_t> acked;               // per peer
  bool timer_running = false;
  std::uint64_t timer_gen = 0;
  unsigned retries = 0;          // T1 expiries in a row without a frame from the far station
  std::vector<bool> gone;        // per peer: its link is down (it no longer holds the window)
  std::vector<unsigned> peer_retries;  // broadcast: per peer, as `retries`
  std::deque<std::pair<MessageId, std::uint64_t>> open;  // message, last sequence number
  SenderStats stats;
};

struct Network::Receiver {
  Sender* sender = nullptr;  // the far end (for message bookkeeping only)
  unsigned station = 0;
  std::size_t peer_index = 0;  // our index in sender->peers
  unsigned ack_line = 0;
  std::uint8_t ack_address = 0;
  std::uint64_t vr = 0;
  bool rej_sent = false;
  Bytes assembly;
  bool ack_pending = false;
  Supervisory ack_kind = Supervisory::RR;
  bool ack_final = false;  // the answer to a poll: F = 1
  Picos ack_due = 0;
  ReceiverStats stats;
};

struct Network::Endpoint {
  unsigned station = 0;
  FaultyWire wire;
  Decoder decoder;
  Picos last_end = 0;
};

struct Network::Line {
  unsigned index = 0;
  unsigned tx_station = 0;
  std::vector<Endpoint> rx;
  std::vector<Sender*> senders;
  std::vector<Receiver*> ackers;  // receivers whose RR/REJ go out on this line
  std::size_t rr_sender = 0, rr_acker = 0;
  bool busy = false;
  Picos wake_at = ~Picos{0};
  LineStats stats;
};

// NC k's link as the RC supervises it, and whether the station still talks.
struct Network::Station {
  bool up = true;
  Picos silent_from = kNever;  // the station sends, answers and takes nothing from here on
  Picos heard = 0;             // the RC last heard a good frame from it
  Picos idle_check_at = kNever;  // a scheduled idle check
  bool poll_queued = false;    // a poll waits for the downstream line
  bool poll_out = false;       // a poll was sent and not answered yet
  unsigned poll_retries = 0;
  std::uint64_t poll_gen = 0;
  SupervisionStats stats;
};

}  // namespace mc1::hdlc
