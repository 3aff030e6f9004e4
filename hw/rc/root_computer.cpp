#include "root_computer.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

#include "sc_time_conv.hpp"

namespace mc1 {

namespace rc {

const char* schedule_name(Schedule s) {
  switch (s) {
    case Schedule::Lpt: return "lpt";
    case Schedule::Fifo: return "fifo";
    case Schedule::Static: return "static";
  }
  return "?";
}

std::optional<Schedule> parse_schedule(const std::string& s) {
  for (Schedule x : {Schedule::Lpt, Schedule::Fifo, Schedule::Static})
    if (s == schedule_name(x)) return x;
  return std::nullopt;
}

}  // namespace rc

namespace {

rc::FramePlan diag_plan(const std::vector<apu::Encoded>& program, rc::SetupMsg setup,
                        std::vector<rc::Block> blocks, std::vector<std::uint32_t> load) {
  rc::FramePlan p;
  p.downloads = {rc::encode(rc::ProgramMsg{program}), rc::encode(setup)};
  p.blocks = std::move(blocks);
  p.load = std::move(load);
  return p;
}

}  // namespace

RootComputer::RootComputer(sc_core::sc_module_name name, const TimingParams& t, unsigned nc_count,
                           std::vector<apu::Encoded> program, rc::SetupMsg setup,
                           std::vector<rc::Block> blocks, std::vector<std::uint32_t> load)
    : RootComputer(name, t, nc_count, diag_plan(program, setup, std::move(blocks), std::move(load))) {}

RootComputer::RootComputer(sc_core::sc_module_name name, const TimingParams& t, unsigned nc_count,
                           rc::FramePlan plan)
    : sc_module(name),
      rc2nc_hdlc("rc2nc_hdlc"),
      hdlc2rc("hdlc2rc"),
      t_(t),
      nc_count_(nc_count),
      plan_(std::move(plan)) {
  if (!plan_.load.empty() && plan_.load.size() != plan_.blocks.size())
    throw std::invalid_argument("RootComputer: " + std::to_string(plan_.load.size()) + " loads for " +
                                std::to_string(plan_.blocks.size()) + " blocks");
  for (std::size_t i = 0; i < plan_.blocks.size(); ++i)
    if (plan_.block_lists && plan_.blocks[i].id != i)
      throw std::invalid_argument("RootComputer: block " + std::to_string(i) + " has id " +
                                  std::to_string(plan_.blocks[i].id) + " (step 2 needs ids 0..n-1)");
  blocks_.resize(plan_.blocks.size());
  dead_.assign(nc_count_ + 1, false);
  parked_.assign(nc_count_ + 1, false);
  finished_.assign(nc_count_ + 1, false);
  asked_.assign(nc_count_ + 1, false);
  lost_.assign(nc_count_ + 1, false);
  own_.resize(nc_count_ + 1);
  if (plan_.block_lists) {
    lists_phase_ = true;
    const std::uint32_t n = plan_.list_jobs ? plan_.list_jobs : nc_count_;
    const auto jobs = static_cast<std::uint32_t>(std::min<std::size_t>(n, plan_.blocks.size()));
    jobs_.resize(jobs);
    for (std::uint32_t j = 0; j < jobs; ++j) jobs_ready_.insert(j);
    lists_.resize(plan_.blocks.size());
    if (jobs == 0) lists_phase_ = false;
  }
  if (!lists_phase_) make_order(plan_.load, false);
  hdlc2rc.register_b_transport(this, &RootComputer::b_transport);
  SC_HAS_PROCESS(RootComputer);
  SC_THREAD(run);
}

namespace {

// base + units x per_unit nanoseconds, in picoseconds, saturating at 2^62
// (53 days: no deadline of a real frame comes near).
Picos deadline_ps(std::uint64_t base_ns, std::uint64_t units, std::uint64_t per_unit_ns) {
  const long double ps = 1000.0L * (static_cast<long double>(base_ns) +
                                    static_cast<long double>(units) * static_cast<long double>(per_unit_ns));
  const long double cap = static_cast<long double>(Picos{1} << 62);
  return static_cast<Picos>(ps < cap ? ps : cap);
}

}  // namespace

Picos RootComputer::block_timeout(std::uint64_t pixels, std::uint64_t work) const {
  return deadline_ps(t_.rc_timeout_base_ns, pixels * (1 + work), t_.rc_timeout_ns_per_pixel_prim);
}

std::uint64_t RootComputer::block_work(std::uint32_t block) const {
  if (!plan_.block_lists) return plan_.load.empty() ? 0 : plan_.load[block];
  if (plan_.object_work.empty()) return lists_[block].load;
  std::uint64_t w = 0;
  for (std::uint16_t o : lists_[block].objects) w += o < plan_.object_work.size() ? plan_.object_work[o] : 1;
  return w;
}

Picos RootComputer::list_job_timeout(std::uint64_t blocks) const {
  return deadline_ps(t_.rc_timeout_base_ns, blocks, t_.rc_timeout_ns_per_list_block);
}

// s4: heaviest predicted blocks first, so that no NC starts a long block at
// the end (lpt); equal loads keep screen order. fifo and static keep screen
// order. `charge`: the RC's processor sorts (step 2 made the loads).
void RootComputer::make_order(const std::vector<std::uint32_t>& load, bool charge) {
  std::vector<std::size_t> idx(plan_.blocks.size());
  std::iota(idx.begin(), idx.end(), 0);
  std::uint64_t compares = 0;
  if (!load.empty() && plan_.schedule == rc::Schedule::Lpt)
    std::stable_sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) {
      ++compares;
      return load[a] > load[b];
    });
  order_.clear();
  rank_of_.assign(plan_.blocks.size(), 0);
  for (std::size_t r = 0; r < idx.size(); ++r) {
    order_.push_back(plan_.blocks[idx[r]]);
    rank_of_[idx[r]] = r;
  }
  if (plan_.schedule == rc::Schedule::Static) {
    for (std::size_t r = 0; r < order_.size(); ++r) own_[r % nc_count_ + 1].insert(r);
  } else {
    for (std::size_t r = 0; r < order_.size(); ++r) ready_.insert(r);
  }
  stats_.sort_compares = compares;
  if (charge) work(compares * t_.mpu_cycles_per_sort_compare);
}

Picos RootComputer::now() const {
  return to_picos(sc_core::sc_time_stamp()) + to_picos(qk_.get_local_time());
}

void RootComputer::work(std::uint64_t mpu_cycles) {
  const Picos ps = t_.mpu_cycles_ps(mpu_cycles);
  stats_.busy += ps;
  qk_.inc(to_sc_time(ps));
  if (qk_.need_sync()) qk_.sync();
}

void RootComputer::post(sc_dt::uint64 address, const rc::Bytes& msg) {
  // Copy the message into the controller's buffer, then start it.
  work((msg.size() + 1) / 2 * t_.mpu_cycles_per_word_copy);
  tlm::tlm_generic_payload p;
  rc::Bytes data = msg;
  p.set_command(tlm::TLM_WRITE_COMMAND);
  p.set_address(address);
  p.set_data_ptr(data.data());
  p.set_data_length(static_cast<unsigned>(data.size()));
  p.set_streaming_width(static_cast<unsigned>(data.size()));
  p.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
  sc_core::sc_time delay = qk_.get_local_time();
  rc2nc_hdlc->b_transport(p, delay);
  if (!p.is_response_ok())
    SC_REPORT_ERROR(name(), ("HDLC refused a message to " + std::to_string(address) + ": " +
                             p.get_response_string())
                                .c_str());
  qk_.set(delay);
  ++stats_.messages_sent;
  stats_.bytes_sent += msg.size();
}

// Tells the HDLC controller to poll idle links from now on, or to stop.
void RootComputer::supervise_links(bool on) {
  HdlcLinkEvent ev(on ? HdlcLinkEvent::Kind::SuperviseOn : HdlcLinkEvent::Kind::SuperviseOff);
  tlm::tlm_generic_payload p;
  p.set_command(tlm::TLM_WRITE_COMMAND);
  p.set_address(kHdlcBroadcast);
  p.set_data_ptr(nullptr);
  p.set_data_length(0);
  p.set_streaming_width(0);
  p.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
  p.set_extension(&ev);
  sc_core::sc_time delay = qk_.get_local_time();
  rc2nc_hdlc->b_transport(p, delay);
  p.clear_extension(&ev);
  if (!p.is_response_ok())
    SC_REPORT_ERROR(name(), ("HDLC refused the supervision command: " + p.get_response_string()).c_str());
}

std::optional<HdlcMailbox::Message> RootComputer::receive(std::optional<Picos> deadline) {
  if (inbox_.empty()) qk_.sync();  // everything due up to our local time has arrived
  std::optional<HdlcMailbox::Message> m;
  if (deadline) {
    if (inbox_.empty() && now() >= *deadline) return std::nullopt;
    m = inbox_.take_until(*deadline);
    if (!m) return std::nullopt;
  } else {
    m = inbox_.take();
  }
  if (m->link_down) {  // the controller's interrupt; no message to copy
    work(t_.mpu_cycles_per_interrupt);
    return m;
  }
  receipts_.push_back({m->arrived, now(), m->from});
  ++stats_.messages_received;
  stats_.bytes_received += m->data.size();
  // Receive interrupt, then copy the message out of the controller's buffer.
  work(t_.mpu_cycles_per_interrupt + (m->data.size() + 1) / 2 * t_.mpu_cycles_per_word_copy);
  return m;
}

void RootComputer::b_transport(tlm::tlm_generic_payload& p, sc_core::sc_time& delay) {
  if (p.get_command() != tlm::TLM_WRITE_COMMAND) {
    p.set_response_status(tlm::TLM_COMMAND_ERROR_RESPONSE);
    return;
  }
  const auto from = static_cast<unsigned>(p.get_address());
  if (from < 1 || from > nc_count_) {
    p.set_response_status(tlm::TLM_ADDRESS_ERROR_RESPONSE);
    return;
  }
  HdlcMailbox::Message m{to_picos(sc_core::sc_time_stamp() + delay), from,
                         rc::Bytes(p.get_data_ptr(), p.get_data_ptr() + p.get_data_length())};
  if (const auto* ev = p.get_extension<HdlcLinkEvent>()) {
    if (ev->kind != HdlcLinkEvent::Kind::LinkDown) {
      p.set_response_status(tlm::TLM_COMMAND_ERROR_RESPONSE);
      return;
    }
    m.link_down = true;
    m.reason = ev->reason;
    m.declared = ev->declared;
  }
  inbox_.put(std::move(m));
  p.set_response_status(tlm::TLM_OK_RESPONSE);
}

void RootComputer::report_block(unsigned nc, std::uint32_t block) {
  if (block >= blocks_.size())
    throw rc::ProtocolError("NC " + std::to_string(nc) + " reported block " + std::to_string(block) + " of " +
                            std::to_string(blocks_.size()));
  Piece& b = blocks_[block];
  if (b.done) {  // a late duplicate: the block was handed out again and done
    ++stats_.late_reports;
    return;
  }
  b.done = true;
  b.owner = 0;
  if (++blocks_done_ == order_.size()) all_done_at_ = now();
  // Done by an NC taken as dead: it may still be queued for another.
  ready_.erase(rank_of_[block]);
  completions_.push_back({now(), nc, block});
  stats_.last_completion = now();
  if (progress_)
    progress_({static_cast<std::uint32_t>(blocks_done_), static_cast<std::uint32_t>(order_.size()), now()});
}

void RootComputer::report_lists(unsigned nc, const rc::ListsMsg& m) {
  const std::uint32_t jobs = static_cast<std::uint32_t>(jobs_.size());
  if (!lists_phase_ || m.job.stride != jobs || m.job.first >= jobs) {
    if (!lists_phase_) {  // step 3 began: a late copy of a job done
      ++stats_.late_reports;
      return;
    }
    throw rc::ProtocolError("NC " + std::to_string(nc) + " sent lists of job (" + std::to_string(m.job.first) +
                            ", " + std::to_string(m.job.stride) + ")");
  }
  Piece& j = jobs_[m.job.first];
  if (j.done) {
    ++stats_.late_reports;
    return;
  }
  const std::vector<std::uint32_t> ids = rc::job_blocks(m.job, plan_.blocks.size());
  if (m.lists.size() != ids.size())
    throw rc::ProtocolError("NC " + std::to_string(nc) + " sent " + std::to_string(m.lists.size()) +
                            " lists for a job of " + std::to_string(ids.size()) + " blocks");
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (!(m.lists[i].block == plan_.blocks[ids[i]]))
      throw rc::ProtocolError("NC " + std::to_string(nc) + " sent the list of block " +
                              std::to_string(m.lists[i].block.id) + " where block " + std::to_string(ids[i]) +
                              " was expected");
    lists_[ids[i]] = m.lists[i];
  }
  work(ids.size() * t_.mpu_cycles_per_list_element);  // file the lists
  j.done = true;
  j.owner = 0;
  jobs_ready_.erase(m.job.first);
  if (std::all_of(jobs_.begin(), jobs_.end(), [](const Piece& p) { return p.done; })) {
    // Step 3 begins: the loads are known.
    lists_phase_ = false;
    stats_.lists_done = now();
    std::vector<std::uint32_t> load(lists_.size());
    for (std::size_t i = 0; i < lists_.size(); ++i) load[i] = lists_[i].load;
    make_order(load, true);
    for (unsigned k = 1; k <= nc_count_; ++k)
      if (dead_[k])
        while (!own_[k].empty()) {  // static: a dead NC's share goes to the others
          ready_.insert(*own_[k].begin());
          own_[k].erase(own_[k].begin());
        }
  }
}

std::optional<std::size_t> RootComputer::next_rank(unsigned nc) const {
  if (plan_.schedule == rc::Schedule::Static && !own_[nc].empty()) return *own_[nc].begin();
  if (!ready_.empty()) return *ready_.begin();
  return std::nullopt;
}

void RootComputer::finish(unsigned nc) {
  dispatches_.push_back({now(), nc, rc::kNoBlock, false});
  post(nc, rc::encode_finish());
  finished_[nc] = true;
  parked_[nc] = false;
}

void RootComputer::serve(unsigned nc) {
  parked_[nc] = false;
  if (finished_[nc]) return;
  if (lists_phase_) {
    if (jobs_ready_.empty()) {
      parked_[nc] = true;  // the other jobs are out; step 3 waits for them
      return;
    }
    work(t_.mpu_cycles_per_list_element);  // take the head of the job list
    const std::uint32_t j = *jobs_ready_.begin();
    jobs_ready_.erase(jobs_ready_.begin());
    const rc::ListJobMsg job{j, static_cast<std::uint32_t>(jobs_.size())};
    jobs_[j].owner = static_cast<int>(nc);
    const Picos at = now();
    dispatches_.push_back({at, nc, j, true});
    jobs_[j].deadline = at + list_job_timeout(rc::job_blocks(job, plan_.blocks.size()).size());
    post(nc, rc::encode(job));
    return;
  }
  work(t_.mpu_cycles_per_list_element);  // look at the head of the block list
  const std::optional<std::size_t> rank = next_rank(nc);
  if (!rank) {
    if (waits_for_pieces_out() && !all_blocks_done())
      parked_[nc] = true;  // blocks are still out: one may come back
    else
      finish(nc);
    return;
  }
  ready_.erase(*rank);
  if (plan_.schedule == rc::Schedule::Static) own_[nc].erase(*rank);
  const rc::Block& b = order_[*rank];
  blocks_[b.id].owner = static_cast<int>(nc);
  const Picos at = now();
  dispatches_.push_back({at, nc, b.id, false});
  blocks_[b.id].deadline = at + block_timeout(std::uint64_t{b.w} * b.h, block_work(b.id));
  if (plan_.block_lists)
    post(nc, rc::encode(rc::AssignListMsg{lists_[b.id]}));
  else
    post(nc, rc::encode(rc::AssignMsg{b}));
}

void RootComputer::serve_parked() {
  for (unsigned k = 1; k <= nc_count_; ++k) {
    if (!parked_[k]) continue;
    if (lists_phase_ ? jobs_ready_.empty() : (!next_rank(k) && !all_blocks_done())) continue;
    serve(k);
  }
}

void RootComputer::requeue_block(std::uint32_t block) {
  Piece& b = blocks_[block];
  b.owner = 0;
  ready_.insert(rank_of_[block]);
  ++stats_.reassigned;
}

std::optional<Picos> RootComputer::next_deadline() const {
  if (!plan_.fault_tolerant) return std::nullopt;
  std::optional<Picos> d;
  auto consider = [&](const Piece& p) {
    if (p.owner && !p.done && !dead_[static_cast<unsigned>(p.owner)] && (!d || p.deadline < *d)) d = p.deadline;
  };
  for (const Piece& p : jobs_) consider(p);
  for (const Piece& p : blocks_) consider(p);
  if (const std::optional<Picos> s = straggler_deadline(); s && (!d || *s < *d)) d = s;
  return d;
}

// Every NC whose deadline has passed is taken as dead; its unfinished
// pieces go back to the queue (in schedule order) for the others.
void RootComputer::expire(Picos t) {
  for (unsigned k = 1; k <= nc_count_; ++k) {
    if (dead_[k]) continue;
    rc::Timeout to;
    bool late = false;
    auto check = [&](const Piece& p, std::uint32_t id, bool job) {
      if (p.owner == static_cast<int>(k) && !p.done && p.deadline <= t && !late) {
        late = true;
        to = rc::Timeout{t, k, id, job, 0};
      }
    };
    for (std::uint32_t j = 0; j < jobs_.size(); ++j) check(jobs_[j], j, true);
    for (std::uint32_t b = 0; b < blocks_.size(); ++b) check(blocks_[b], b, false);
    if (!late) continue;
    dead_[k] = true;
    to.requeued = take_back(k);
    timeouts_.push_back(to);
  }
  if (const std::optional<Picos> s = straggler_deadline(); s && *s <= t)
    for (unsigned k = 1; k <= nc_count_; ++k)
      if (!asked_[k] && !dead_[k] && !finished_[k]) {
        dead_[k] = true;
        timeouts_.push_back(rc::Timeout{t, k, rc::kNoBlock, false, 0});
      }
}

// NC `nc`'s unfinished pieces go back to the queue (in schedule order) for
// the others; static: its remaining share goes to the common queue.
std::uint32_t RootComputer::take_back(unsigned nc) {
  std::uint32_t n = 0;
  for (std::uint32_t j = 0; j < jobs_.size(); ++j)
    if (jobs_[j].owner == static_cast<int>(nc) && !jobs_[j].done) {
      jobs_[j].owner = 0;
      jobs_ready_.insert(j);
      ++stats_.reassigned;
      ++n;
    }
  for (std::uint32_t b = 0; b < blocks_.size(); ++b)
    if (blocks_[b].owner == static_cast<int>(nc) && !blocks_[b].done) {
      requeue_block(b);
      ++n;
    }
  while (!own_[nc].empty()) {
    ready_.insert(*own_[nc].begin());
    own_[nc].erase(own_[nc].begin());
  }
  return n;
}

// The controller gave NC k's link up: the NC is lost for the frame at once
// (it cannot report, so it is never revived); its work goes to the others.
void RootComputer::link_down(const HdlcMailbox::Message& m) {
  const unsigned k = m.from;
  rc::LinkDown d{m.declared, now(), k, m.reason, 0};
  if (!lost_[k]) {
    lost_[k] = true;
    dead_[k] = true;
    parked_[k] = false;
    d.requeued = take_back(k);
  }
  link_downs_.push_back(d);
}

// Work left that no NC can ever take is an error, not a wait forever.
void RootComputer::check_progress_possible() const {
  for (unsigned k = 1; k <= nc_count_; ++k)
    if (!lost_[k] && !finished_[k]) return;
  throw std::runtime_error("the frame cannot complete: every NC has finished or lost its link (" + status() + ")");
}

// An NC that never asked for work (it stopped before its first request)
// has until rc_timeout_base_ns after the frame's last block.
std::optional<Picos> RootComputer::straggler_deadline() const {
  if (!plan_.fault_tolerant || lists_phase_ || !all_blocks_done()) return std::nullopt;
  for (unsigned k = 1; k <= nc_count_; ++k)
    if (!asked_[k] && !dead_[k] && !finished_[k]) return all_done_at_ + 1000 * t_.rc_timeout_base_ns;
  return std::nullopt;
}

std::string RootComputer::status() const {
  unsigned dead = 0, finished = 0;
  for (unsigned k = 1; k <= nc_count_; ++k) {
    dead += dead_[k] && !finished_[k];
    finished += finished_[k];
  }
  return std::to_string(blocks_done_) + " of " + std::to_string(blocks_.size()) + " blocks done" +
         (lists_phase_ ? " (block lists not complete)" : "") + ", " + std::to_string(finished) + " of " +
         std::to_string(nc_count_) + " NCs finished, " + std::to_string(dead) + " taken as dead, " +
         std::to_string(timeouts_.size()) + " deadlines missed, " + std::to_string(link_downs_.size()) +
         " links down";
}

bool RootComputer::frame_complete() const {
  if (lists_phase_ || !all_blocks_done()) return false;
  for (unsigned k = 1; k <= nc_count_; ++k)
    if (!finished_[k] && !dead_[k]) return false;
  return true;
}

void RootComputer::handle(const HdlcMailbox::Message& m) {
  if (m.link_down) {
    link_down(m);
    return;
  }
  const unsigned k = m.from;
  if (lost_[k]) return;  // its controller dropped the link: nothing more from it counts
  asked_[k] = true;
  if (dead_[k] && !finished_[k]) {  // it missed a deadline but is alive: back to work
    dead_[k] = false;
    ++stats_.revived;
  }
  switch (rc::type_of(m.data)) {
    case rc::MsgType::Request: {
      const rc::RequestMsg req = rc::decode_request(m.data);
      if (finished_[k]) throw rc::ProtocolError("NC " + std::to_string(k) + " asked again after Finish");
      if (req.done_block != rc::kNoBlock) report_block(k, req.done_block);
      serve(k);
      break;
    }
    case rc::MsgType::Lists: {
      if (finished_[k]) throw rc::ProtocolError("NC " + std::to_string(k) + " sent lists after Finish");
      report_lists(k, rc::decode_lists(m.data));
      serve(k);
      break;
    }
    default:
      throw rc::ProtocolError("NC " + std::to_string(k) + " sent message type " + std::to_string(m.data[0]) +
                              " where a request was expected");
  }
}

void RootComputer::run() {
  try {
    supervise_links(true);
    // s2: download by broadcast, then start.
    for (const rc::Bytes& d : plan_.downloads) {
      post(kHdlcBroadcast, d);
      stats_.download_bytes += d.size();
    }
    stats_.setup_done = now();

    while (!frame_complete()) {
      check_progress_possible();
      const std::optional<Picos> deadline = next_deadline();
      const std::optional<HdlcMailbox::Message> m = receive(deadline);
      if (m)
        handle(*m);
      else
        expire(now());
      serve_parked();
    }
    done_ = true;
    stats_.done_at = now();
    supervise_links(false);  // nothing to watch for any more: the simulation can end
    qk_.sync();
    // An NC taken as dead may still be alive: tell it to stop when it asks.
    for (;;) {
      const std::optional<HdlcMailbox::Message> m = receive(std::nullopt);
      if (m->link_down) {
        link_down(*m);
        continue;
      }
      if (lost_[m->from]) continue;
      const rc::MsgType type = rc::type_of(m->data);
      if ((type == rc::MsgType::Request || type == rc::MsgType::Lists) && !finished_[m->from]) {
        if (type == rc::MsgType::Request) {
          const rc::RequestMsg req = rc::decode_request(m->data);
          if (req.done_block != rc::kNoBlock) report_block(m->from, req.done_block);
        } else {
          ++stats_.late_reports;
        }
        finish(m->from);
        qk_.sync();
      }
    }
  } catch (const std::exception& e) {
    supervise_links(false);  // no polls for ever after a failed frame
    SC_REPORT_ERROR(name(), e.what());
  }
}

}  // namespace mc1
