#include "rc_dispatcher.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>

namespace mc1::rc {

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

// ---------------------------------------------------------------- NC states

const char* nc_state_name(NcState s) {
  switch (s) {
    case NcState::Starting: return "starting";
    case NcState::Working: return "working";
    case NcState::Parked: return "parked";
    case NcState::Finished: return "finished";
    case NcState::Dead: return "dead";
    case NcState::Lost: return "lost";
  }
  return "?";
}

// Every transition the RC makes, and no other:
//   serving an NC's request (Starting, Working, Parked) -> Working (a piece),
//     Parked (nothing ready, pieces out) or Finished;
//   a deadline passing (Working; Starting: it never asked) -> Dead;
//   an NC taken as dead that reports after all: Dead -> Working (revived),
//     or, once the frame is complete, Dead -> Finished;
//   a link going down: anything but Lost -> Lost.
// Parked -> Parked happens only to an NC that asks again while it waits,
// Parked -> Dead only to one that asked without reporting the piece it held
// (the RC answers such requests as any other; the piece keeps its
// deadline). Finished and Lost are final but for Finished -> Lost.
bool transition_allowed(NcState from, NcState to) {
  using S = NcState;
  switch (from) {
    case S::Starting:
    case S::Working:
    case S::Parked: return to != S::Starting;
    case S::Dead: return to == S::Working || to == S::Finished || to == S::Lost;
    case S::Finished: return to == S::Lost;
    case S::Lost: return false;
  }
  return false;
}

void NcStates::to(unsigned nc, NcState next) {
  const NcState from = s_.at(nc);
  if (!transition_allowed(from, next))
    throw std::logic_error("RC: NC " + std::to_string(nc) + " cannot go from " + nc_state_name(from) + " to " +
                           nc_state_name(next));
  s_[nc] = next;
}

unsigned NcStates::count(NcState s) const {
  return static_cast<unsigned>(std::count(s_.begin() + 1, s_.end(), s));
}

bool NcStates::taken_as_dead(unsigned nc) const {
  return s_.at(nc) == NcState::Dead || s_.at(nc) == NcState::Lost;
}

// ---------------------------------------------------------------- set-up

Dispatcher::Dispatcher(const TimingParams& t, unsigned nc_count, FramePlan plan, RcPort& port)
    : t_(t), nc_count_(nc_count), plan_(std::move(plan)), port_(port), states_(nc_count) {
  check_plan();
  blocks_.resize(plan_.blocks.size());
  own_.resize(nc_count_ + 1);
  if (plan_.block_lists) start_lists_phase();
  if (!lists_phase_) make_order(plan_.load, false);
}

void Dispatcher::check_plan() const {
  if (!plan_.load.empty() && plan_.load.size() != plan_.blocks.size())
    throw std::invalid_argument("RootComputer: " + std::to_string(plan_.load.size()) + " loads for " +
                                std::to_string(plan_.blocks.size()) + " blocks");
  for (std::size_t i = 0; i < plan_.blocks.size(); ++i)
    if (plan_.block_lists && plan_.blocks[i].id != i)
      throw std::invalid_argument("RootComputer: block " + std::to_string(i) + " has id " +
                                  std::to_string(plan_.blocks[i].id) + " (step 2 needs ids 0..n-1)");
}

// Step 2: the list jobs (one per NC unless the plan says), none with no blocks.
void Dispatcher::start_lists_phase() {
  const std::uint32_t n = plan_.list_jobs ? plan_.list_jobs : nc_count_;
  const auto jobs = static_cast<std::uint32_t>(std::min<std::size_t>(n, plan_.blocks.size()));
  jobs_.resize(jobs);
  for (std::uint32_t j = 0; j < jobs; ++j) jobs_ready_.insert(j);
  lists_.resize(plan_.blocks.size());
  lists_phase_ = jobs > 0;
}

// s4: heaviest predicted blocks first, so that no NC starts a long block at
// the end (lpt); equal loads keep screen order. fifo and static keep screen
// order. `charge`: the RC's processor sorts (step 2 made the loads).
void Dispatcher::make_order(const std::vector<std::uint32_t>& load, bool charge) {
  std::vector<std::size_t> idx(plan_.blocks.size());
  std::iota(idx.begin(), idx.end(), 0);
  std::uint64_t compares = 0;
  if (!load.empty() && plan_.schedule == Schedule::Lpt)
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
  for (std::size_t r = 0; r < order_.size(); ++r) {
    if (plan_.schedule == Schedule::Static)
      own_[r % nc_count_ + 1].insert(r);
    else
      ready_.insert(r);
  }
  stats_.sort_compares = compares;
  if (charge) port_.work(compares * t_.mpu_cycles_per_sort_compare);
}

// Step 3 begins: every block list is in, so the loads are known.
void Dispatcher::start_step3() {
  lists_phase_ = false;
  stats_.lists_done = port_.now();
  std::vector<std::uint32_t> load(lists_.size());
  for (std::size_t i = 0; i < lists_.size(); ++i) load[i] = lists_[i].load;
  make_order(load, true);
  for (unsigned k = 1; k <= nc_count_; ++k)
    if (states_.taken_as_dead(k)) release_share(k);  // static: a dead NC's share goes to the others
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

// Deadline of a block of `pixels` pixels and `work` per pixel (the weighted
// primitives of its list, or its load), from its dispatch (docs/timing.md).
Picos Dispatcher::block_timeout(std::uint64_t pixels, std::uint64_t work) const {
  return deadline_ps(t_.rc_timeout_base_ns, pixels * (1 + work), t_.rc_timeout_ns_per_pixel_prim);
}

std::uint64_t Dispatcher::block_work(std::uint32_t block) const {
  if (!plan_.block_lists) return plan_.load.empty() ? 0 : plan_.load[block];
  if (plan_.object_work.empty()) return lists_[block].load;
  std::uint64_t w = 0;
  for (std::uint16_t o : lists_[block].objects) w += o < plan_.object_work.size() ? plan_.object_work[o] : 1;
  return w;
}

// Deadline of a list job of `blocks` blocks, from its dispatch.
Picos Dispatcher::list_job_timeout(std::uint64_t blocks) const {
  return deadline_ps(t_.rc_timeout_base_ns, blocks, t_.rc_timeout_ns_per_list_block);
}

// ---------------------------------------------------------------- messages

void Dispatcher::on_message(unsigned k, const Bytes& msg) {
  const NcState s = states_[k];
  if (s == NcState::Lost) return;  // its controller dropped the link: nothing more from it counts
  if (s == NcState::Dead) {        // it missed a deadline but is alive: back to work
    states_.to(k, NcState::Working);
    ++stats_.revived;
  }
  switch (type_of(msg)) {
    case MsgType::Request: {
      const RequestMsg req = decode_request(msg);
      if (s == NcState::Finished) throw ProtocolError("NC " + std::to_string(k) + " asked again after Finish");
      if (req.done_block != kNoBlock) report_block(k, req.done_block);
      serve(k);
      break;
    }
    case MsgType::Lists: {
      if (s == NcState::Finished) throw ProtocolError("NC " + std::to_string(k) + " sent lists after Finish");
      report_lists(k, decode_lists(msg));
      serve(k);
      break;
    }
    default:
      throw ProtocolError("NC " + std::to_string(k) + " sent message type " + std::to_string(msg[0]) +
                          " where a request was expected");
  }
}

// An NC taken as dead may still be alive: it is told to stop when it asks
// (what it reports is late by now).
bool Dispatcher::on_message_after_frame(unsigned k, const Bytes& msg) {
  const NcState s = states_[k];
  if (s == NcState::Lost) return false;
  const MsgType type = type_of(msg);
  if (s == NcState::Finished || (type != MsgType::Request && type != MsgType::Lists)) return false;
  if (type == MsgType::Request) {
    const RequestMsg req = decode_request(msg);
    if (req.done_block != kNoBlock) report_block(k, req.done_block);
  } else {
    ++stats_.late_reports;
  }
  finish(k);
  return true;
}

void Dispatcher::report_block(unsigned nc, std::uint32_t block) {
  if (block >= blocks_.size() || lists_phase_)
    throw ProtocolError("NC " + std::to_string(nc) + " reported block " + std::to_string(block) + " of " +
                        std::to_string(blocks_.size()) + (lists_phase_ ? " before step 3" : ""));
  Piece& b = blocks_[block];
  if (b.done) {  // a late duplicate: the block was handed out again and done
    ++stats_.late_reports;
    return;
  }
  b.done = true;
  b.owner = 0;
  const Picos now = port_.now();
  if (++blocks_done_ == order_.size()) all_done_at_ = now;
  // Done by an NC taken as dead: it may still be queued for another.
  ready_.erase(rank_of_[block]);
  completions_.push_back({now, nc, block});
  stats_.last_completion = now;
  if (progress_)
    progress_({static_cast<std::uint32_t>(blocks_done_), static_cast<std::uint32_t>(order_.size()), now});
}

void Dispatcher::report_lists(unsigned nc, const ListsMsg& m) {
  const auto jobs = static_cast<std::uint32_t>(jobs_.size());
  if (!lists_phase_) {  // step 3 began: a late copy of a job done
    ++stats_.late_reports;
    return;
  }
  if (m.job.stride != jobs || m.job.first >= jobs)
    throw ProtocolError("NC " + std::to_string(nc) + " sent lists of job (" + std::to_string(m.job.first) + ", " +
                        std::to_string(m.job.stride) + ")");
  Piece& j = jobs_[m.job.first];
  if (j.done) {
    ++stats_.late_reports;
    return;
  }
  const std::vector<std::uint32_t> ids = job_blocks(m.job, plan_.blocks.size());
  check_lists(nc, m, ids);
  for (std::size_t i = 0; i < ids.size(); ++i) lists_[ids[i]] = m.lists[i];
  port_.work(ids.size() * t_.mpu_cycles_per_list_element);  // file the lists
  j.done = true;
  j.owner = 0;
  jobs_ready_.erase(m.job.first);
  if (std::all_of(jobs_.begin(), jobs_.end(), [](const Piece& p) { return p.done; })) start_step3();
}

void Dispatcher::check_lists(unsigned nc, const ListsMsg& m, const std::vector<std::uint32_t>& ids) const {
  if (m.lists.size() != ids.size())
    throw ProtocolError("NC " + std::to_string(nc) + " sent " + std::to_string(m.lists.size()) +
                        " lists for a job of " + std::to_string(ids.size()) + " blocks");
  for (std::size_t i = 0; i < ids.size(); ++i)
    if (!(m.lists[i].block == plan_.blocks[ids[i]]))
      throw ProtocolError("NC " + std::to_string(nc) + " sent the list of block " +
                          std::to_string(m.lists[i].block.id) + " where block " + std::to_string(ids[i]) +
                          " was expected");
}

// ---------------------------------------------------------------- serving

void Dispatcher::serve(unsigned nc) {
  if (lists_phase_) {
    if (jobs_ready_.empty())
      states_.to(nc, NcState::Parked);  // the other jobs are out; step 3 waits for them
    else
      hand_out_job(nc);
    return;
  }
  port_.work(t_.mpu_cycles_per_list_element);  // look at the head of the block list
  const std::optional<std::size_t> rank = next_rank(nc);
  if (rank)
    hand_out_block(nc, *rank);
  else if (waits_for_pieces_out() && !all_blocks_done())
    states_.to(nc, NcState::Parked);  // blocks are still out: one may come back
  else
    finish(nc);
}

void Dispatcher::hand_out_job(unsigned nc) {
  port_.work(t_.mpu_cycles_per_list_element);  // take the head of the job list
  const std::uint32_t j = *jobs_ready_.begin();
  jobs_ready_.erase(jobs_ready_.begin());
  const ListJobMsg job{j, static_cast<std::uint32_t>(jobs_.size())};
  states_.to(nc, NcState::Working);
  jobs_[j].owner = nc;
  const Picos at = port_.now();
  dispatches_.push_back({at, nc, j, true});
  jobs_[j].deadline = at + list_job_timeout(job_blocks(job, plan_.blocks.size()).size());
  port_.send(nc, encode(job));
}

void Dispatcher::hand_out_block(unsigned nc, std::size_t rank) {
  ready_.erase(rank);
  if (plan_.schedule == Schedule::Static) own_[nc].erase(rank);
  const Block& b = order_[rank];
  states_.to(nc, NcState::Working);
  blocks_[b.id].owner = nc;
  const Picos at = port_.now();
  dispatches_.push_back({at, nc, b.id, false});
  blocks_[b.id].deadline = at + block_timeout(std::uint64_t{b.w} * b.h, block_work(b.id));
  if (plan_.block_lists)
    port_.send(nc, encode(AssignListMsg{lists_[b.id]}));
  else
    port_.send(nc, encode(AssignMsg{b}));
}

void Dispatcher::finish(unsigned nc) {
  dispatches_.push_back({port_.now(), nc, kNoBlock, false});
  port_.send(nc, encode_finish());
  states_.to(nc, NcState::Finished);
}

std::optional<std::size_t> Dispatcher::next_rank(unsigned nc) const {
  if (plan_.schedule == Schedule::Static && !own_[nc].empty()) return *own_[nc].begin();
  if (!ready_.empty()) return *ready_.begin();
  return std::nullopt;
}

void Dispatcher::serve_parked() {
  for (unsigned k = 1; k <= nc_count_; ++k) {
    if (states_[k] != NcState::Parked) continue;
    if (lists_phase_ ? jobs_ready_.empty() : (!next_rank(k) && !all_blocks_done())) continue;
    serve(k);
  }
}

// ---------------------------------------------------------------- faults

std::optional<Picos> Dispatcher::next_deadline() const {
  if (!plan_.fault_tolerant) return std::nullopt;
  std::optional<Picos> d;
  auto consider = [&](const Piece& p) {
    if (p.owner && !p.done && !states_.taken_as_dead(p.owner) && (!d || p.deadline < *d)) d = p.deadline;
  };
  for (const Piece& p : jobs_) consider(p);
  for (const Piece& p : blocks_) consider(p);
  if (const std::optional<Picos> s = straggler_deadline(); s && (!d || *s < *d)) d = s;
  return d;
}

// NC nc's first unfinished piece (list jobs first) whose deadline is t or earlier.
std::optional<Timeout> Dispatcher::overdue(unsigned nc, Picos t) const {
  for (std::uint32_t j = 0; j < jobs_.size(); ++j)
    if (jobs_[j].owner == nc && !jobs_[j].done && jobs_[j].deadline <= t) return Timeout{t, nc, j, true, 0};
  for (std::uint32_t b = 0; b < blocks_.size(); ++b)
    if (blocks_[b].owner == nc && !blocks_[b].done && blocks_[b].deadline <= t) return Timeout{t, nc, b, false, 0};
  return std::nullopt;
}

// Every NC whose deadline has passed is taken as dead; its unfinished
// pieces go back to the queue (in schedule order) for the others.
void Dispatcher::expire() {
  const Picos t = port_.now();
  for (unsigned k = 1; k <= nc_count_; ++k) {
    if (states_.taken_as_dead(k)) continue;
    std::optional<Timeout> to = overdue(k, t);
    if (!to) continue;
    states_.to(k, NcState::Dead);
    to->requeued = take_back(k);
    timeouts_.push_back(*to);
  }
  expire_stragglers(t);
}

void Dispatcher::expire_stragglers(Picos t) {
  const std::optional<Picos> s = straggler_deadline();
  if (!s || *s > t) return;
  for (unsigned k = 1; k <= nc_count_; ++k)
    if (states_[k] == NcState::Starting) {
      states_.to(k, NcState::Dead);
      timeouts_.push_back(Timeout{t, k, kNoBlock, false, 0});
    }
}

// An NC that never asked for work (it stopped before its first request)
// has until rc_timeout_base_ns after the frame's last block.
std::optional<Picos> Dispatcher::straggler_deadline() const {
  if (!plan_.fault_tolerant || lists_phase_ || !all_blocks_done()) return std::nullopt;
  for (unsigned k = 1; k <= nc_count_; ++k)
    if (states_[k] == NcState::Starting) return all_done_at_ + 1000 * t_.rc_timeout_base_ns;
  return std::nullopt;
}

// NC `nc`'s unfinished pieces go back to the queue (in schedule order) for
// the others; static: its remaining share goes to the common queue.
std::uint32_t Dispatcher::take_back(unsigned nc) {
  std::uint32_t n = 0;
  for (std::uint32_t j = 0; j < jobs_.size(); ++j)
    if (jobs_[j].owner == nc && !jobs_[j].done) {
      jobs_[j].owner = 0;
      jobs_ready_.insert(j);
      ++stats_.reassigned;
      ++n;
    }
  for (std::uint32_t b = 0; b < blocks_.size(); ++b)
    if (blocks_[b].owner == nc && !blocks_[b].done) {
      requeue_block(b);
      ++n;
    }
  release_share(nc);
  return n;
}

void Dispatcher::release_share(unsigned nc) {
  ready_.insert(own_[nc].begin(), own_[nc].end());
  own_[nc].clear();
}

void Dispatcher::requeue_block(std::uint32_t block) {
  blocks_[block].owner = 0;
  ready_.insert(rank_of_[block]);
  ++stats_.reassigned;
}

// The controller gave NC k's link up: the NC is lost for the frame at once
// (it cannot report, so it is never revived); its work goes to the others.
void Dispatcher::on_link_down(unsigned k, hdlc::LinkDownReason why, Picos declared) {
  LinkDown d{declared, port_.now(), k, why, 0};
  if (states_[k] != NcState::Lost) {
    states_.to(k, NcState::Lost);
    d.requeued = take_back(k);
  }
  link_downs_.push_back(d);
}

// ---------------------------------------------------------------- the frame

// Work left that no NC can ever take is an error, not a wait forever.
void Dispatcher::check_progress_possible() const {
  for (unsigned k = 1; k <= nc_count_; ++k)
    if (states_[k] != NcState::Lost && states_[k] != NcState::Finished) return;
  throw std::runtime_error("the frame cannot complete: every NC has finished or lost its link (" + status() + ")");
}

bool Dispatcher::frame_complete() const {
  if (lists_phase_ || !all_blocks_done()) return false;
  for (unsigned k = 1; k <= nc_count_; ++k)
    if (states_[k] != NcState::Finished && !states_.taken_as_dead(k)) return false;
  return true;
}

std::string Dispatcher::status() const {
  const unsigned dead = states_.count(NcState::Dead) + states_.count(NcState::Lost);
  return std::to_string(blocks_done_) + " of " + std::to_string(blocks_.size()) + " blocks done" +
         (lists_phase_ ? " (block lists not complete)" : "") + ", " +
         std::to_string(states_.count(NcState::Finished)) + " of " + std::to_string(nc_count_) +
         " NCs finished, " + std::to_string(dead) + " taken as dead, " + std::to_string(timeouts_.size()) +
         " deadlines missed, " + std::to_string(link_downs_.size()) + " links down";
}

}  // namespace mc1::rc
