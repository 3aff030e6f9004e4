// The messages between the root computer and its node computers (s2, s4:
// the RC broadcasts programs and data, starts the NCs, hands out blocks of
// the screen dynamically; an NC asks for the next block when it is done).
// They travel as HDLC messages (docs/hdlc.md); docs/platform.md "The RC's
// protocol" gives the byte layout. All integers little-endian.
#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "microword.hpp"

namespace mc1::rc {

using Bytes = std::vector<std::uint8_t>;

enum class MsgType : std::uint8_t {
  Program = 0x01,  // RC -> all: the APU program
  Setup = 0x02,    // RC -> all: frame size; the NCs start asking for blocks
  Request = 0x10,  // NC -> RC: give me a block (and: this one is done)
  Assign = 0x11,   // RC -> NC: compute this block
  Finish = 0x12,   // RC -> NC: no block left
};

constexpr std::uint32_t kNoBlock = 0xFFFFFFFF;

// A rectangle of the screen (s4: the RC splits the screen into blocks).
struct Block {
  std::uint32_t id = 0;
  std::uint16_t x = 0, y = 0, w = 0, h = 0;
  bool operator==(const Block& o) const {
    return id == o.id && x == o.x && y == o.y && w == o.w && h == o.h;
  }
};

struct ProgramMsg {
  std::vector<apu::Encoded> words;
};
struct SetupMsg {
  std::uint16_t width = 0, height = 0;
};
struct RequestMsg {
  std::uint32_t done_block = kNoBlock;  // the block just finished, or kNoBlock
};
struct AssignMsg {
  Block block;
};

class ProtocolError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

Bytes encode(const ProgramMsg& m);
Bytes encode(const SetupMsg& m);
Bytes encode(const RequestMsg& m);
Bytes encode(const AssignMsg& m);
Bytes encode_finish();

// The type of a message; throws ProtocolError on an empty or unknown one.
MsgType type_of(const Bytes& msg);
// Decoders throw ProtocolError naming the type and the length on a malformed message.
ProgramMsg decode_program(const Bytes& msg);
SetupMsg decode_setup(const Bytes& msg);
RequestMsg decode_request(const Bytes& msg);
AssignMsg decode_assign(const Bytes& msg);

// The screen cut into blocks of bw x bh pixels, row by row (the last column
// and row of blocks clipped at the screen's edge); ids 0, 1, ... in that order.
std::vector<Block> split_screen(unsigned width, unsigned height, unsigned bw, unsigned bh);

}  // namespace mc1::rc
