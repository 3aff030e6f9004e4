#include "hdlc_link.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "hdlc_link_state.hpp"

namespace mc1::hdlc {

const char* link_down_reason_name(LinkDownReason r) {
  switch (r) {
    case LinkDownReason::RetryLimit: return "retry limit";
    case LinkDownReason::PollUnanswered: return "poll unanswered";
  }
  return "?";
}

// ---------------------------------------------------------------- faults

FaultyWire::FaultyWire(LinkFaults f) : f_(std::move(f)), rng_(f_.seed) {
  std::sort(f_.flip_bits.begin(), f_.flip_bits.end());
  draw_gap();
}

// splitmix64: tiny, portable, so a seed means the same flips everywhere.
std::uint64_t FaultyWire::next_random() {
  std::uint64_t z = (rng_ += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

// Independent flips with probability p: the gap to the next one is geometric.
void FaultyWire::draw_gap() {
  if (f_.bit_error_rate <= 0.0) {
    gap_ = std::numeric_limits<std::uint64_t>::max();
    return;
  }
  if (f_.bit_error_rate >= 1.0) {
    gap_ = 0;
    return;
  }
  const double u = (static_cast<double>(next_random() >> 11) + 1.0) * 0x1.0p-53;  // (0,1]
  const double g = std::floor(std::log(u) / std::log1p(-f_.bit_error_rate));
  gap_ = g >= 1.8e19 ? std::numeric_limits<std::uint64_t>::max() : static_cast<std::uint64_t>(g);
}

Bits FaultyWire::receive(const Bits& sent, Picos start, std::uint64_t bit_rate_bps) {
  Bits out = sent;
  for (std::size_t i = 0; i < out.size(); ++i, ++seen_) {
    bool dead = false;
    if (!f_.dead.empty()) {
      const Picos t = start + static_cast<Picos>(static_cast<unsigned __int128>(i) *
                                                 1'000'000'000'000ULL / bit_rate_bps);
      for (const DeadWindow& w : f_.dead) dead = dead || (t >= w.begin && t < w.end);
    }
    bool flip = std::binary_search(f_.flip_bits.begin(), f_.flip_bits.end(), seen_);
    if (gap_ == 0) {
      flip = !flip;
      draw_gap();
    } else if (gap_ != std::numeric_limits<std::uint64_t>::max()) {
      --gap_;
    }
    if (dead) {
      out[i] = 1;  // a dead line marks: the receiver sees idle
      ++dead_;
    } else if (flip) {
      out[i] ^= 1;
      ++flipped_;
    }
  }
  return out;
}

// ---------------------------------------------------------------- set-up

Network::Network(const TimingParams& t, unsigned nc_count) : t_(t), nc_count_(nc_count) {
  if (nc_count < 1 || nc_count > kAddrNcLast)
    throw std::invalid_argument("hdlc::Network: NC count must be 1..254");
  t_.validate();
  for (unsigned l = 0; l <= nc_count; ++l) {
    auto line = std::make_unique<Line>();
    line->index = l;
    line->tx_station = l;  // line 0 is the RC's, line k is NC k's
    if (l == 0)
      for (unsigned k = 1; k <= nc_count; ++k) line->rx.push_back(Endpoint{k, FaultyWire{}, Decoder{}, 0});
    else
      line->rx.push_back(Endpoint{0, FaultyWire{}, Decoder{}, 0});
    lines_.push_back(std::move(line));
  }
  auto make_sender = [](std::uint8_t addr, unsigned line, unsigned from,
                        std::vector<unsigned> peers) {
    auto s = std::make_unique<Sender>();
    s->address = addr;
    s->line = line;
    s->from_station = from;
    s->acked.assign(peers.size(), 0);
    s->gone.assign(peers.size(), false);
    s->peer_retries.assign(peers.size(), 0);
    s->peers = std::move(peers);
    return s;
  };
  auto make_receiver = [](Sender* s, unsigned station, std::size_t peer, unsigned ack_line,
                          std::uint8_t ack_addr) {
    auto r = std::make_unique<Receiver>();
    r->sender = s;
    r->station = station;
    r->peer_index = peer;
    r->ack_line = ack_line;
    r->ack_address = ack_addr;
    return r;
  };
  std::vector<unsigned> all;
  for (unsigned k = 1; k <= nc_count; ++k) all.push_back(k);
  broadcast_ = make_sender(kAddrBroadcast, 0, 0, all);
  for (unsigned k = 1; k <= nc_count; ++k) {
    const auto addr = static_cast<std::uint8_t>(k);
    to_nc_.push_back(make_sender(addr, 0, 0, {k}));
    to_rc_.push_back(make_sender(kAddrRc, k, k, {0}));
    at_nc_.push_back(make_receiver(to_nc_.back().get(), k, 0, k, kAddrRc));
    bcast_at_nc_.push_back(make_receiver(broadcast_.get(), k, k - 1, k, kAddrBroadcast));
    at_rc_.push_back(make_receiver(to_rc_.back().get(), 0, 0, 0, addr));
    to_nc_.back()->reverse = at_rc_.back().get();
    to_rc_.back()->reverse = at_nc_.back().get();
    lines_[0]->senders.push_back(to_nc_.back().get());
    lines_[0]->ackers.push_back(at_rc_.back().get());
    lines_[k]->senders.push_back(to_rc_.back().get());
    lines_[k]->ackers.push_back(at_nc_.back().get());
    lines_[k]->ackers.push_back(bcast_at_nc_.back().get());
  }
  lines_[0]->senders.push_back(broadcast_.get());
  stations_.resize(nc_count);
}

Network::~Network() = default;

void Network::set_faults(Direction d, unsigned nc, const LinkFaults& f) {
  if (nc < 1 || nc > nc_count_) throw std::out_of_range("hdlc::Network::set_faults: bad NC");
  Endpoint& ep = d == Direction::Down ? lines_[0]->rx[nc - 1] : lines_[nc]->rx[0];
  ep.wire = FaultyWire(f);
}

void Network::silence(unsigned nc, Picos from) {
  if (nc < 1 || nc > nc_count_) throw std::out_of_range("hdlc::Network::silence: no NC " + std::to_string(nc));
  Station& st = stations_[nc - 1];
  st.silent_from = std::min(st.silent_from, from);
}

void Network::supervise(bool on, Picos when) {
  at_external(when, 0, [this, on] {
    supervising_ = on;
    if (!on || t_.hdlc_poll_interval_ns == 0) return;
    // Idle from now on: the first poll goes out one interval later.
    for (unsigned k = 1; k <= nc_count_; ++k) {
      stations_[k - 1].heard = std::max(stations_[k - 1].heard, now_);
      schedule_idle_check(k, now_ + t_.hdlc_poll_interval_ns * 1000);
    }
  });
}

bool Network::silent(unsigned nc) const { return now_ >= stations_[nc - 1].silent_from; }

bool Network::link_up(unsigned nc) const { return stations_.at(nc - 1).up; }

std::vector<LinkDown> Network::take_link_downs() {
  std::vector<LinkDown> d(link_downs_.begin() + static_cast<long>(link_downs_taken_), link_downs_.end());
  link_downs_taken_ = link_downs_.size();
  return d;
}

// ---------------------------------------------------------------- events

void Network::at(Picos t, std::function<void()> fn) {
  events_.push(Event{std::max(t, now_), Event::kInternal, ev_seq_++, std::move(fn)});
}

void Network::at_external(Picos t, unsigned from, std::function<void()> fn) {
  events_.push(Event{std::max(t, now_), from, ev_seq_++, std::move(fn)});
}

void Network::step() {
  // Moved out, not copied (a frame rides in it): pop() orders by t and seq alone.
  Event e = std::move(const_cast<Event&>(events_.top()));
  events_.pop();
  now_ = e.t;
  e.fn();
}

void Network::run_until(Picos t) {
  while (!events_.empty() && events_.top().t <= t) step();
  now_ = std::max(now_, t);
}

bool Network::run_until_complete(MessageId id, Picos limit) {
  while (!settled(id)) {
    if (events_.empty() || events_.top().t > limit) return false;
    step();
  }
  return messages_[id].complete;
}

bool Network::all_complete() const {
  return std::all_of(messages_.begin(), messages_.end(),
                     [](const MessageStatus& m) { return m.complete; });
}

bool Network::run_until_all_complete(Picos limit) {
  auto all_settled = [this] {
    return std::all_of(messages_.begin(), messages_.end(),
                       [](const MessageStatus& m) { return m.complete || m.lost; });
  };
  while (!all_settled()) {
    if (events_.empty() || events_.top().t > limit) return false;
    step();
  }
  return all_complete();
}

std::optional<Picos> Network::next_event() const {
  if (events_.empty()) return std::nullopt;
  return events_.top().t;
}

// ---------------------------------------------------------------- sending

MessageId Network::send(Picos when, unsigned from, std::uint8_t address, Bytes data) {
  Sender* s = nullptr;
  if (from == 0 && address == kAddrBroadcast) {
    s = broadcast_.get();
  } else if (from == 0 && address >= 1 && address <= nc_count_) {
    s = to_nc_[address - 1].get();
  } else if (from >= 1 && from <= nc_count_ && address == kAddrRc) {
    s = to_rc_[from - 1].get();
  } else {
    throw std::invalid_argument("hdlc::Network::send: no link from station " +
                                std::to_string(from) + " to address " + std::to_string(address));
  }
  const MessageId id = messages_.size();
  MessageStatus st;
  st.from_station = from;
  st.address = address;
  st.delivered.assign(s->peers.size(), 0);
  const std::size_t chunk = t_.hdlc_max_info_bytes - 1;
  st.frames = data.empty() ? 1 : (data.size() + chunk - 1) / chunk;
  messages_.push_back(st);
  at_external(when, from, [this, s, id, data = std::move(data), chunk] {
    messages_[id].submitted = now_;
    // A link that is down takes nothing (for a broadcast: when every NC's is).
    if (std::all_of(s->gone.begin(), s->gone.end(), [](bool g) { return g; })) {
      messages_[id].lost = true;
      return;
    }
    const std::size_t n = messages_[id].frames;
    for (std::size_t i = 0; i < n; ++i) {
      Segment seg;
      seg.msg = id;
      seg.info.push_back(i + 1 == n ? 1 : 0);  // segment octet: bit 0 = last
      const std::size_t b = i * chunk, e = std::min(data.size(), b + chunk);
      seg.info.insert(seg.info.end(), data.begin() + b, data.begin() + e);
      s->frames.push_back(std::move(seg));
    }
    s->open.emplace_back(id, s->base + s->frames.size() - 1);
    try_transmit(*lines_[s->line]);
  });
  return id;
}

bool Network::sendable(const Sender& s) const {
  if (s.next < s.highest) return true;  // going back: resend
  return s.next < s.base + s.frames.size() && s.next - s.base < t_.hdlc_window;
}

void Network::try_transmit(Line& l) {
  if (l.busy) return;
  if (l.index != 0 && silent(l.index)) return;  // a stopped station sends nothing
  Picos earliest = ~Picos{0};
  // Acknowledgements first: they free the far end's window; then polls.
  if (transmit_ack(l, earliest) || transmit_poll(l)) return;
  const std::size_t ns = l.senders.size();
  for (std::size_t i = 0; i < ns; ++i) {
    Sender& s = *l.senders[(l.rr_sender + i) % ns];
    if (!sendable(s)) continue;
    l.rr_sender = (l.rr_sender + i + 1) % ns;
    const std::uint64_t seq = s.next++;
    const bool again = seq < s.highest;
    if (!again) s.highest = seq + 1;
    ++s.stats.i_frames;
    if (again) {
      ++s.stats.retransmissions;
      ++l.stats.retransmissions;
    }
    std::uint8_t nr = 0;
    if (s.reverse) {
      nr = static_cast<std::uint8_t>(s.reverse->vr & 7);
      // The piggybacked N(R) is as good as a pending RR (not as the answer to a poll).
      if (s.reverse->ack_pending && s.reverse->ack_kind == Supervisory::RR && !s.reverse->ack_final) {
        s.reverse->ack_pending = false;
      }
    }
    Frame f;
    f.address = s.address;
    f.control = Control::info(static_cast<std::uint8_t>(seq & 7), nr).octet();
    f.info = s.frames[seq - s.base].info;
    transmit(l, f, &s);
    return;
  }
  if (earliest != ~Picos{0} && earliest != l.wake_at) {
    l.wake_at = earliest;
    at(earliest, [this, &l, earliest] {
      if (l.wake_at == earliest) l.wake_at = ~Picos{0};
      try_transmit(l);
    });
  }
}

// The next due RR/REJ of the line, if any; `earliest`: when one falls due.
bool Network::transmit_ack(Line& l, Picos& earliest) {
  const std::size_t na = l.ackers.size();
  for (std::size_t i = 0; i < na; ++i) {
    Receiver& r = *l.ackers[(l.rr_acker + i) % na];
    if (!r.ack_pending) continue;
    if (r.ack_due > now_) {
      earliest = std::min(earliest, r.ack_due);
      continue;
    }
    l.rr_acker = (l.rr_acker + i + 1) % na;
    r.ack_pending = false;
    (r.ack_kind == Supervisory::REJ ? r.stats.rej_sent : r.stats.rr_sent)++;
    Frame f;
    f.address = r.ack_address;
    f.control = Control::super(r.ack_kind, static_cast<std::uint8_t>(r.vr & 7), r.ack_final).octet();
    r.ack_final = false;
    transmit(l, f, nullptr);
    return true;
  }
  return false;
}

// The RC's next queued poll (downstream only): RR with P = 1 to the NC. Its
// N(R) acknowledges the NC's frames like any RR.
bool Network::transmit_poll(Line& l) {
  if (l.index != 0) return false;
  for (unsigned i = 0; i < nc_count_; ++i) {
    const unsigned k = static_cast<unsigned>((rr_poll_ + i) % nc_count_) + 1;
    Station& st = stations_[k - 1];
    if (!st.poll_queued) continue;
    rr_poll_ = k % nc_count_;
    st.poll_queued = false;
    ++st.stats.polls;
    Receiver& r = *at_rc_[k - 1];
    if (r.ack_pending && r.ack_kind == Supervisory::RR) r.ack_pending = false;
    Frame f;
    f.address = static_cast<std::uint8_t>(k);
    f.control = Control::super(Supervisory::RR, static_cast<std::uint8_t>(r.vr & 7), true).octet();
    transmit(l, f, nullptr, k);
    return true;
  }
  return false;
}

void Network::transmit(Line& l, Frame f, Sender* s, unsigned poll_nc) {
  if (trace_) trace_(now_, l.index, f);
  const std::size_t bits = wire_bits(f);
  const Picos start = now_;
  const Picos dur = t_.hdlc_bits_ps(bits);
  l.busy = true;
  ++l.stats.frames;
  (s ? l.stats.i_frames : l.stats.s_frames)++;
  if (!s && (f.control & 0x10)) ++l.stats.poll_frames;
  if (s) l.stats.info_bytes += f.info.size();
  l.stats.wire_bits += bits;
  at(start + dur, [this, &l, f = std::move(f), bits, start, s, poll_nc] {
    frame_end(l, f, bits, start, s, poll_nc);
  });
}

void Network::start_timer(Sender& s, Picos from) {
  s.timer_running = true;
  const std::uint64_t gen = ++s.timer_gen;
  at(from + t_.hdlc_t1_timeout_ns * 1000, [this, &s, gen] {
    if (!s.timer_running || gen != s.timer_gen) return;
    s.timer_running = false;
    if (s.base < s.highest) t1_expired(s);
  });
}

// One more T1 expiry without a frame from station `nc`'s end: false once
// N2 retries were counted already (the link has failed).
bool Network::count_retry(unsigned& retries, unsigned nc) {
  if (retries >= t_.hdlc_n2_retries) return false;
  ++retries;
  SupervisionStats& st = stations_[nc - 1].stats;
  st.max_retries = std::max(st.max_retries, retries);
  return true;
}

// T1 expired with frames outstanding: count a retry against every far end
// that stayed silent (N2 reached: the link is down), then go back to the
// oldest unacknowledged frame (for a broadcast, the slowest NC's) and send
// everything again.
void Network::t1_expired(Sender& s) {
  ++s.stats.timeouts;
  if (s.from_station != 0) {
    // The NC's own sender: at N2 the station gives up and falls silent,
    // waiting for a link set-up from the RC (not modelled).
    const unsigned k = s.from_station;
    if (!count_retry(s.retries, k)) {
      stations_[k - 1].stats.station_gave_up = true;
      silence(k, now_);
      return;
    }
  } else if (&s == broadcast_.get()) {
    for (std::size_t i = 0; i < s.peers.size(); ++i)
      if (!s.gone[i] && s.acked[i] < s.highest && !count_retry(s.peer_retries[i], s.peers[i]))
        link_down(s.peers[i], LinkDownReason::RetryLimit);
    if (s.base >= s.highest) return;  // only NCs now gone were behind
  } else if (!count_retry(s.retries, s.peers[0])) {
    link_down(s.peers[0], LinkDownReason::RetryLimit);
    return;
  }
  s.next = s.base;
  try_transmit(*lines_[s.line]);
}

// ---------------------------------------------------------------- results

const MessageStatus& Network::status(MessageId id) const { return messages_.at(id); }

std::vector<Delivery> Network::take_deliveries() {
  std::vector<Delivery> d;
  d.swap(deliveries_);
  return d;
}

const LineStats& Network::down_line() const { return lines_[0]->stats; }
const LineStats& Network::up_line(unsigned nc) const { return lines_.at(nc)->stats; }

ReceiveStats Network::receive_stats(Direction d, unsigned nc) const {
  const Endpoint& ep = d == Direction::Down ? lines_[0]->rx.at(nc - 1) : lines_.at(nc)->rx[0];
  return ReceiveStats{ep.decoder.counters(), ep.wire.bits_flipped(), ep.wire.bits_dead()};
}

const SenderStats& Network::sender_to_nc(unsigned nc) const { return to_nc_.at(nc - 1)->stats; }
const SenderStats& Network::sender_broadcast() const { return broadcast_->stats; }
const SenderStats& Network::sender_to_rc(unsigned nc) const { return to_rc_.at(nc - 1)->stats; }
const ReceiverStats& Network::receiver_at_nc(unsigned nc) const {
  return at_nc_.at(nc - 1)->stats;
}
const ReceiverStats& Network::broadcast_receiver_at_nc(unsigned nc) const {
  return bcast_at_nc_.at(nc - 1)->stats;
}
const SupervisionStats& Network::supervision(unsigned nc) const { return stations_.at(nc - 1).stats; }

}  // namespace mc1::hdlc
