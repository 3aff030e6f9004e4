#include "rc_protocol.hpp"

#include <algorithm>

namespace mc1::rc {
namespace {

void put16(Bytes& b, std::uint16_t v) {
  b.push_back(static_cast<std::uint8_t>(v));
  b.push_back(static_cast<std::uint8_t>(v >> 8));
}
void put32(Bytes& b, std::uint32_t v) {
  put16(b, static_cast<std::uint16_t>(v));
  put16(b, static_cast<std::uint16_t>(v >> 16));
}
void put64(Bytes& b, std::uint64_t v) {
  put32(b, static_cast<std::uint32_t>(v));
  put32(b, static_cast<std::uint32_t>(v >> 32));
}
std::uint64_t get(const Bytes& b, std::size_t at, int bytes) {
  std::uint64_t v = 0;
  for (int i = bytes - 1; i >= 0; --i) v = (v << 8) | b[at + static_cast<std::size_t>(i)];
  return v;
}

void expect(const Bytes& m, MsgType t, std::size_t length, const char* what) {
  if (m.empty() || m[0] != static_cast<std::uint8_t>(t) || m.size() != length)
    throw ProtocolError(std::string("malformed ") + what + " message: " + std::to_string(m.size()) +
                        " bytes, type 0x" + (m.empty() ? std::string("--") : std::to_string(m[0])) +
                        ", expected " + std::to_string(length) + " bytes");
}

}  // namespace

Bytes encode(const ProgramMsg& m) {
  Bytes b{static_cast<std::uint8_t>(MsgType::Program)};
  put16(b, static_cast<std::uint16_t>(m.words.size()));
  for (const apu::Encoded& w : m.words) {
    put64(b, w.lo);
    put64(b, w.hi);
  }
  return b;
}

Bytes encode(const SetupMsg& m) {
  Bytes b{static_cast<std::uint8_t>(MsgType::Setup)};
  put16(b, m.width);
  put16(b, m.height);
  return b;
}

Bytes encode(const RequestMsg& m) {
  Bytes b{static_cast<std::uint8_t>(MsgType::Request)};
  put32(b, m.done_block);
  return b;
}

Bytes encode(const AssignMsg& m) {
  Bytes b{static_cast<std::uint8_t>(MsgType::Assign)};
  put32(b, m.block.id);
  put16(b, m.block.x);
  put16(b, m.block.y);
  put16(b, m.block.w);
  put16(b, m.block.h);
  return b;
}

Bytes encode_finish() { return Bytes{static_cast<std::uint8_t>(MsgType::Finish)}; }

MsgType type_of(const Bytes& msg) {
  if (msg.empty()) throw ProtocolError("empty message");
  switch (static_cast<MsgType>(msg[0])) {
    case MsgType::Program:
    case MsgType::Setup:
    case MsgType::Request:
    case MsgType::Assign:
    case MsgType::Finish:
    case MsgType::Download:
    case MsgType::RenderSetup:
    case MsgType::ListJob:
    case MsgType::Lists:
    case MsgType::AssignList: return static_cast<MsgType>(msg[0]);
  }
  throw ProtocolError("unknown message type " + std::to_string(msg[0]));
}

ProgramMsg decode_program(const Bytes& msg) {
  if (msg.size() < 3) expect(msg, MsgType::Program, 3, "program");
  const std::size_t n = get(msg, 1, 2);
  expect(msg, MsgType::Program, 3 + 16 * n, "program");
  ProgramMsg m;
  m.words.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    m.words[i].lo = get(msg, 3 + 16 * i, 8);
    m.words[i].hi = get(msg, 3 + 16 * i + 8, 8);
  }
  return m;
}

SetupMsg decode_setup(const Bytes& msg) {
  expect(msg, MsgType::Setup, 5, "setup");
  return SetupMsg{static_cast<std::uint16_t>(get(msg, 1, 2)), static_cast<std::uint16_t>(get(msg, 3, 2))};
}

RequestMsg decode_request(const Bytes& msg) {
  expect(msg, MsgType::Request, 5, "request");
  return RequestMsg{static_cast<std::uint32_t>(get(msg, 1, 4))};
}

AssignMsg decode_assign(const Bytes& msg) {
  expect(msg, MsgType::Assign, 13, "assign");
  AssignMsg m;
  m.block.id = static_cast<std::uint32_t>(get(msg, 1, 4));
  m.block.x = static_cast<std::uint16_t>(get(msg, 5, 2));
  m.block.y = static_cast<std::uint16_t>(get(msg, 7, 2));
  m.block.w = static_cast<std::uint16_t>(get(msg, 9, 2));
  m.block.h = static_cast<std::uint16_t>(get(msg, 11, 2));
  return m;
}

Bytes encode(const DownloadMsg& m) {
  Bytes b(2 + m.payload.size());
  b[0] = static_cast<std::uint8_t>(MsgType::Download);
  b[1] = m.tag;
  std::copy(m.payload.begin(), m.payload.end(), b.begin() + 2);
  return b;
}

Bytes encode(const RenderSetupMsg& m) {
  Bytes b{static_cast<std::uint8_t>(MsgType::RenderSetup)};
  put16(b, m.width);
  put16(b, m.height);
  put16(b, m.block_w);
  put16(b, m.block_h);
  return b;
}

Bytes encode(const ListJobMsg& m) {
  Bytes b{static_cast<std::uint8_t>(MsgType::ListJob)};
  put32(b, m.first);
  put32(b, m.stride);
  return b;
}

namespace {

void put_list(Bytes& b, const BlockListMsg& l) {
  if (l.objects.size() > 0xFFFF) throw ProtocolError("block list of " + std::to_string(l.objects.size()) + " objects");
  put32(b, l.block.id);
  put16(b, l.block.x);
  put16(b, l.block.y);
  put16(b, l.block.w);
  put16(b, l.block.h);
  put32(b, l.load);
  put16(b, static_cast<std::uint16_t>(l.objects.size()));
  for (std::uint16_t o : l.objects) put16(b, o);
}

// Reads one block list at `at`; false if the message ends inside it.
bool get_list(const Bytes& b, std::size_t& at, BlockListMsg& l) {
  if (at + 18 > b.size()) return false;
  l.block.id = static_cast<std::uint32_t>(get(b, at, 4));
  l.block.x = static_cast<std::uint16_t>(get(b, at + 4, 2));
  l.block.y = static_cast<std::uint16_t>(get(b, at + 6, 2));
  l.block.w = static_cast<std::uint16_t>(get(b, at + 8, 2));
  l.block.h = static_cast<std::uint16_t>(get(b, at + 10, 2));
  l.load = static_cast<std::uint32_t>(get(b, at + 12, 4));
  const std::size_t n = get(b, at + 16, 2);
  at += 18;
  if (at + 2 * n > b.size()) return false;
  l.objects.resize(n);
  for (std::size_t i = 0; i < n; ++i) l.objects[i] = static_cast<std::uint16_t>(get(b, at + 2 * i, 2));
  at += 2 * n;
  return true;
}

[[noreturn]] void malformed(const Bytes& m, const char* what) {
  throw ProtocolError(std::string("malformed ") + what + " message: " + std::to_string(m.size()) + " bytes");
}

}  // namespace

Bytes encode(const ListsMsg& m) {
  Bytes b{static_cast<std::uint8_t>(MsgType::Lists)};
  put32(b, m.job.first);
  put32(b, m.job.stride);
  put32(b, static_cast<std::uint32_t>(m.lists.size()));
  for (const BlockListMsg& l : m.lists) put_list(b, l);
  return b;
}

Bytes encode(const AssignListMsg& m) {
  Bytes b{static_cast<std::uint8_t>(MsgType::AssignList)};
  put_list(b, m.list);
  return b;
}

DownloadMsg decode_download(const Bytes& msg) {
  if (msg.size() < 2 || msg[0] != static_cast<std::uint8_t>(MsgType::Download)) malformed(msg, "download");
  return DownloadMsg{msg[1], Bytes(msg.begin() + 2, msg.end())};
}

RenderSetupMsg decode_render_setup(const Bytes& msg) {
  expect(msg, MsgType::RenderSetup, 9, "render setup");
  return RenderSetupMsg{static_cast<std::uint16_t>(get(msg, 1, 2)), static_cast<std::uint16_t>(get(msg, 3, 2)),
                        static_cast<std::uint16_t>(get(msg, 5, 2)), static_cast<std::uint16_t>(get(msg, 7, 2))};
}

ListJobMsg decode_list_job(const Bytes& msg) {
  expect(msg, MsgType::ListJob, 9, "list job");
  const ListJobMsg m{static_cast<std::uint32_t>(get(msg, 1, 4)), static_cast<std::uint32_t>(get(msg, 5, 4))};
  if (m.stride == 0) throw ProtocolError("list job with stride 0");
  return m;
}

ListsMsg decode_lists(const Bytes& msg) {
  if (msg.size() < 13 || msg[0] != static_cast<std::uint8_t>(MsgType::Lists)) malformed(msg, "lists");
  ListsMsg m;
  m.job.first = static_cast<std::uint32_t>(get(msg, 1, 4));
  m.job.stride = static_cast<std::uint32_t>(get(msg, 5, 4));
  const std::size_t n = get(msg, 9, 4);
  std::size_t at = 13;
  for (std::size_t i = 0; i < n; ++i) {
    BlockListMsg l;
    if (!get_list(msg, at, l)) malformed(msg, "lists");
    m.lists.push_back(std::move(l));
  }
  if (at != msg.size()) malformed(msg, "lists");
  return m;
}

AssignListMsg decode_assign_list(const Bytes& msg) {
  if (msg.empty() || msg[0] != static_cast<std::uint8_t>(MsgType::AssignList)) malformed(msg, "assign-list");
  AssignListMsg m;
  std::size_t at = 1;
  if (!get_list(msg, at, m.list) || at != msg.size()) malformed(msg, "assign-list");
  return m;
}

std::vector<std::uint32_t> job_blocks(const ListJobMsg& job, std::size_t block_count) {
  std::vector<std::uint32_t> out;
  for (std::size_t i = job.first; i < block_count; i += job.stride) out.push_back(static_cast<std::uint32_t>(i));
  return out;
}

std::vector<Block> split_screen(unsigned width, unsigned height, unsigned bw, unsigned bh) {
  if (width == 0 || height == 0 || bw == 0 || bh == 0 || width > 0xFFFF || height > 0xFFFF)
    throw ProtocolError("split_screen: bad size " + std::to_string(width) + "x" + std::to_string(height) +
                        " or block " + std::to_string(bw) + "x" + std::to_string(bh));
  std::vector<Block> out;
  for (unsigned y = 0; y < height; y += bh)
    for (unsigned x = 0; x < width; x += bw)
      out.push_back(Block{static_cast<std::uint32_t>(out.size()), static_cast<std::uint16_t>(x),
                          static_cast<std::uint16_t>(y), static_cast<std::uint16_t>(std::min(bw, width - x)),
                          static_cast<std::uint16_t>(std::min(bh, height - y))});
  return out;
}

}  // namespace mc1::rc
