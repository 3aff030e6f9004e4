// The messages between the root computer and its node computers (s2, s4:
// the RC broadcasts programs and data, starts the NCs, hands out blocks of
// the screen dynamically; an NC asks for the next block when it is done).
// They travel as HDLC messages (docs/hdlc.md); docs/platform.md "The RC's
// protocol" gives the byte layout. All integers little-endian.
//
// Two frames use them: the diagnostic frame (Program, Setup, then Request /
// Assign / Finish) and the rendered frame of fig. 3 (Download of kernels and
// scene, RenderSetup; step 2: ListJob / Lists; step 3: Request /
// AssignList / Finish).
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
  Download = 0x03,     // RC -> all: a tagged payload of the frame's firmware (kernel, scene)
  RenderSetup = 0x04,  // RC -> all: frame and block size; the NCs start step 1
  Request = 0x10,  // NC -> RC: give me a block (and: this one is done)
  Assign = 0x11,   // RC -> NC: compute this block
  Finish = 0x12,   // RC -> NC: no block left
  ListJob = 0x13,     // RC -> NC: build the block lists of these blocks (step 2)
  Lists = 0x14,       // NC -> RC: the block lists of a job (and: give me work)
  AssignList = 0x15,  // RC -> NC: render this block; its block list (step 3)
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

// Download tags of the rendered frame (the payload is the firmware's business).
enum class DownloadTag : std::uint8_t { Kernel = 1, Scene = 2 };
struct DownloadMsg {
  std::uint8_t tag = 0;
  Bytes payload;
};
struct RenderSetupMsg {
  std::uint16_t width = 0, height = 0, block_w = 0, block_h = 0;
};
// Step 2 job: blocks first, first + stride, first + 2 stride, ... of
// split_screen(width, height, block_w, block_h) of the RenderSetup.
struct ListJobMsg {
  std::uint32_t first = 0, stride = 1;
};
// s2 of fig. 3: a block's list of objects, nearest first, and its predicted
// load (s4: the RC hands out the heaviest first).
struct BlockListMsg {
  Block block;
  std::uint32_t load = 0;
  std::vector<std::uint16_t> objects;
  bool operator==(const BlockListMsg& o) const {
    return block == o.block && load == o.load && objects == o.objects;
  }
};
struct ListsMsg {
  ListJobMsg job;
  std::vector<BlockListMsg> lists;  // in job order
};
struct AssignListMsg {
  BlockListMsg list;
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
Bytes encode(const DownloadMsg& m);
Bytes encode(const RenderSetupMsg& m);
Bytes encode(const ListJobMsg& m);
Bytes encode(const ListsMsg& m);
Bytes encode(const AssignListMsg& m);

// The type of a message; throws ProtocolError on an empty or unknown one.
MsgType type_of(const Bytes& msg);
// Decoders throw ProtocolError naming the type and the length on a malformed message.
ProgramMsg decode_program(const Bytes& msg);
SetupMsg decode_setup(const Bytes& msg);
RequestMsg decode_request(const Bytes& msg);
AssignMsg decode_assign(const Bytes& msg);
DownloadMsg decode_download(const Bytes& msg);
RenderSetupMsg decode_render_setup(const Bytes& msg);
ListJobMsg decode_list_job(const Bytes& msg);
ListsMsg decode_lists(const Bytes& msg);
AssignListMsg decode_assign_list(const Bytes& msg);

// The blocks of a list job, in order.
std::vector<std::uint32_t> job_blocks(const ListJobMsg& job, std::size_t block_count);

// The screen cut into blocks of bw x bh pixels, row by row (the last column
// and row of blocks clipped at the screen's edge); ids 0, 1, ... in that order.
std::vector<Block> split_screen(unsigned width, unsigned height, unsigned bw, unsigned bh);

}  // namespace mc1::rc
