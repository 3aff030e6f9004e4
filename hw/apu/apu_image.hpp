// The APU program image (docs/apu-asm.md, "Output"): "APU1", the word count
// (u32 LE), then per microword lo (u64 LE) and hi (u64 LE). The assembler
// writes it; the MPU firmware, the test benches and the tools load it.
#pragma once

#include <string>
#include <vector>

#include "microword.hpp"

namespace mc1::apu {

std::string image_bytes(const std::vector<Encoded>& words);
// Throws std::runtime_error naming `name` on a bad image.
std::vector<Encoded> parse_image(const std::string& bytes, const std::string& name = "<image>");
void write_image(const std::string& path, const std::vector<Encoded>& words);
std::vector<Encoded> load_image(const std::string& path);

}  // namespace mc1::apu
