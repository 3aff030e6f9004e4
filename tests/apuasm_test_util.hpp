// Helpers of the apuasm_*_test.cpp and apu_disasm_test.cpp programs: one line
// assembled, the diagnostics of a source that must not assemble, a scratch
// directory.
#pragma once

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

#include "apuasm.hpp"
#include "microword.hpp"

namespace mc1::apuasm {

using apu::AddOp;
using apu::Encoded;
using apu::FuncOp;
using apu::IntOp;
using apu::MemOp;
using apu::MicroWord;
using apu::SeqOp;

inline Encoded one(const std::string& line) {
  const auto p = assemble(line + "\n", "t.apu");
  EXPECT_EQ(p.words.size(), 1u) << line;
  return p.words.empty() ? Encoded{} : p.words[0];
}

inline MicroWord decoded(const std::string& line) { return MicroWord::decode(one(line)); }

// The diagnostics of a source that must not assemble.
inline std::vector<std::string> errors(const std::string& src, const std::string& file = "e.apu") {
  try {
    assemble(src, file);
  } catch (const AsmError& e) {
    std::vector<std::string> out;
    for (const auto& d : e.diagnostics()) out.push_back(d.str());
    return out;
  }
  ADD_FAILURE() << "assembled without error:\n" << src;
  return {};
}

inline std::string first_error(const std::string& src) {
  const auto e = errors(src);
  return e.empty() ? "" : e[0];
}

// A scratch directory for .include tests, removed at the end.
class TempDir {
 public:
  TempDir() {
    char tmpl[] = "/tmp/apuasm_test_XXXXXX";
    path_ = mkdtemp(tmpl);
  }
  ~TempDir() {
    for (const auto& f : files_) std::remove(f.c_str());
    for (auto it = dirs_.rbegin(); it != dirs_.rend(); ++it) rmdir(it->c_str());
    rmdir(path_.c_str());
  }
  std::string write(const std::string& name, const std::string& text) {
    const std::string p = path_ + "/" + name;
    const auto slash = name.find('/');
    if (slash != std::string::npos) {
      dirs_.push_back(path_ + "/" + name.substr(0, slash));
      mkdir(dirs_.back().c_str(), 0700);
    }
    std::ofstream(p) << text;
    files_.push_back(p);
    return p;
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::vector<std::string> files_, dirs_;
};


// `parens` parentheses around `minuses` unary minus signs before 1.
inline std::string nested(int parens, int minuses) {
  return std::string(static_cast<size_t>(parens), '(') + std::string(static_cast<size_t>(minuses), '-') + "1" +
         std::string(static_cast<size_t>(parens), ')');
}

}  // namespace mc1::apuasm
