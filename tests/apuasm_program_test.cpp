// The apuasm program (host/apuasm/apuasm_main.cpp): exit status 0 / 1 / 2,
// its outputs and options (docs/apu-asm.md).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <dirent.h>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "apu_image.hpp"
#include "apuasm_test_util.hpp"

namespace mc1::apuasm {
namespace {

// ---------------------------------------------------------------------------
// The program: exit status 0 / 1 (an output not written, none left) / 2
// (usage or input), the options of docs/apu-asm.md.

// build/bin/apuasm, beside this test program.
std::string apuasm_program() {
  char buf[4096];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n <= 0) return "apuasm";
  const std::string self(buf, static_cast<size_t>(n));
  return self.substr(0, self.find_last_of('/')) + "/apuasm";
}

struct Run {
  int status = -1;
  std::string out, err;
};

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// Runs apuasm with `args` (shell words), in `dir` for its output files.
Run run_apuasm(const TempDir& dir, const std::string& args) {
  const std::string out = dir.path() + "/.stdout", err = dir.path() + "/.stderr";
  const std::string cmd = "cd '" + dir.path() + "' && '" + apuasm_program() + "' " + args + " >'" + out + "' 2>'" + err + "'";
  const int rc = std::system(cmd.c_str());
  Run r;
  r.status = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  std::remove(out.c_str());
  std::remove(err.c_str());
  return r;
}

std::set<std::string> names_in(const std::string& path) {
  std::set<std::string> out;
  DIR* d = opendir(path.c_str());
  if (!d) return out;
  while (const dirent* e = readdir(d))
    if (std::string(e->d_name) != "." && std::string(e->d_name) != "..") out.insert(e->d_name);
  closedir(d);
  return out;
}

bool exists(const std::string& path) {
  struct stat st {};
  return stat(path.c_str(), &st) == 0;
}

TEST(ApuAsmProgram, WritesImageListingAndHex) {
  TempDir dir;
  const std::string src = "start: mul f1, f2, f3\n  halt\n";
  dir.write("k.apu", src);
  const auto r = run_apuasm(dir, "-l k.lst -x k.hex k.apu");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto p = assemble(src, "k.apu");
  EXPECT_EQ(slurp(dir.path() + "/k.bin"), image_bytes(p.words));  // default: the source name with .bin
  EXPECT_EQ(slurp(dir.path() + "/k.lst"), listing_text(p));
  EXPECT_EQ(slurp(dir.path() + "/k.hex"), readmemh_text(p.words));
  const auto d = run_apuasm(dir, "-d k.bin");
  EXPECT_EQ(d.status, 0) << d.err;
  EXPECT_EQ(d.out, disassembly_text(p.words));
  for (const char* f : {"/k.bin", "/k.lst", "/k.hex"}) std::remove((dir.path() + f).c_str());
}

TEST(ApuAsmProgram, FailedWriteExitsOneAndLeavesNoOutput) {
  TempDir dir;
  dir.write("k.apu", "halt\n");
  auto r = run_apuasm(dir, "-o /dev/full k.apu");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, "apuasm: /dev/full: cannot write: No space left on device\n");
  struct stat st {};
  ASSERT_EQ(stat("/dev/full", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode)) << "the device was replaced";
  // The image is written, the listing is not: neither is left.
  r = run_apuasm(dir, "-o k.bin -l /dev/full k.apu");
  EXPECT_EQ(r.status, 1);
  EXPECT_FALSE(exists(dir.path() + "/k.bin"));
  r = run_apuasm(dir, "-o no/such/dir/k.bin k.apu");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("no/such/dir/k.bin: cannot create a temporary file beside it"), std::string::npos) << r.err;
  EXPECT_EQ(names_in(dir.path()), std::set<std::string>{"k.apu"}) << "a temporary file was left";
}

TEST(ApuAsmProgram, UsageAndInputErrorsExitTwo) {
  TempDir dir;
  dir.write("bad.apu", "frob\n");
  dir.write("sub/x.inc", "nop\n");
  auto r = run_apuasm(dir, "bad.apu");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "bad.apu:1:1: error: unknown mnemonic 'frob'\n");
  EXPECT_FALSE(exists(dir.path() + "/bad.bin"));
  r = run_apuasm(dir, "sub");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "sub: error: cannot read file: is a directory\n");
  r = run_apuasm(dir, "missing.apu");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "missing.apu: error: cannot read file: No such file or directory\n");
  r = run_apuasm(dir, "-d bad.apu");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "apuasm: bad.apu: not an APU image (no \"APU1\" header)\n");
  for (const char* args : {"", "--frob bad.apu", "-o", "a.apu b.apu", "-d x.bin bad.apu", "-d x.bin -o y.bin"}) {
    r = run_apuasm(dir, args);
    EXPECT_EQ(r.status, 2) << args;
    EXPECT_EQ(r.err.rfind("apuasm: ", 0), 0u) << args << ": " << r.err;
  }
}

// A nesting that crashed the program (exit 139) and a source without end
// are input errors, exit 2, nothing written.
TEST(ApuAsmProgram, DeepExpressionAndEndlessSourceExitTwo) {
  TempDir dir;
  dir.write("deep.apu", ".equ X, " + nested(60000, 0) + "\n");
  auto r = run_apuasm(dir, "deep.apu");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err,
            "deep.apu:1:265: error: expression nested deeper than 256 levels of parentheses and unary operators\n");
  r = run_apuasm(dir, "-o z.bin /dev/zero");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "/dev/zero: error: cannot read file: larger than 16 MiB\n");
  EXPECT_EQ(names_in(dir.path()), std::set<std::string>{"deep.apu"});
}

// An output that is an input (by name, "./", "..", a hard or symbolic link),
// or two outputs that are one file: a usage error before anything is written.
TEST(ApuAsmProgram, OutputsMustNotReplaceInputsOrEachOther) {
  TempDir dir;
  const std::string src = "halt\n";
  dir.write("k.apu", src);
  dir.write("x.bin", src);
  dir.write("sub/x.inc", "nop\n");
  dir.write("top.apu", ".include \"sub/x.inc\"\nhalt\n");
  const std::string hard = dir.path() + "/h.apu", soft = dir.path() + "/s.apu";
  ASSERT_EQ(link((dir.path() + "/k.apu").c_str(), hard.c_str()), 0);
  ASSERT_EQ(symlink("k.apu", soft.c_str()), 0);
  const auto before = names_in(dir.path());
  const std::pair<const char*, const char*> cases[] = {
      {"k.apu -o k.apu", "-o k.apu would replace the source k.apu"},
      {"k.apu -l ./k.apu", "-l ./k.apu would replace the source k.apu"},
      {"k.apu -x sub/../k.apu", "-x sub/../k.apu would replace the source k.apu"},
      {"k.apu -o h.apu", "-o h.apu would replace the source k.apu"},
      {"s.apu -l k.apu", "-l k.apu would replace the source s.apu"},
      {"x.bin", "-o (default) x.bin would replace the source x.bin"},
      {"k.apu -o y.bin -l y.bin", "-o and -l name one file: y.bin"},
      {"k.apu -o y.bin -x ./y.bin", "-o and -x name one file: ./y.bin"},
      {"k.apu -l y.lst -x sub/../y.lst", "-l and -x name one file: sub/../y.lst"},
      {"k.apu -l k.bin", "-l and -o (default) name one file: k.bin"},
      {"top.apu -l sub/x.inc -o t.bin", "-l sub/x.inc would replace the include file sub/x.inc"},
  };
  for (const auto& [args, message] : cases) {
    const auto r = run_apuasm(dir, args);
    EXPECT_EQ(r.status, 2) << args;
    EXPECT_EQ(r.err, "apuasm: " + std::string(message) + "\n") << args;
    EXPECT_EQ(names_in(dir.path()), before) << args;
  }
  EXPECT_EQ(slurp(dir.path() + "/k.apu"), src);
  EXPECT_EQ(slurp(dir.path() + "/sub/x.inc"), "nop\n");
  // A device is written in place: two outputs to /dev/null are no loss.
  EXPECT_EQ(run_apuasm(dir, "k.apu -o /dev/null -l /dev/null").status, 0);
  std::remove(hard.c_str());
  std::remove(soft.c_str());
}

TEST(ApuAsmProgram, HelpAndVersion) {
  TempDir dir;
  auto r = run_apuasm(dir, "--help");
  EXPECT_EQ(r.status, 0);
  for (const char* opt : {"-o FILE", "-l FILE", "-x FILE", "-d FILE", "--version", "SOURCE.apu"})
    EXPECT_NE(r.out.find(opt), std::string::npos) << opt << " missing from\n" << r.out;
  r = run_apuasm(dir, "--version");
  EXPECT_EQ(r.status, 0);
  const std::string prefix = "apuasm (MC-1 virtual platform) ";  // every program's form
  ASSERT_EQ(r.out.rfind(prefix, 0), 0u) << r.out;
  const std::string version = r.out.substr(prefix.size());  // CMake's project(VERSION), e.g. "0.1.0\n"
  EXPECT_GE(version.size(), 6u) << r.out;
  EXPECT_EQ(version.find_first_not_of("0123456789.\n"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace mc1::apuasm
