// cmdline::Files: every file option of a program declared once, checked by
// one call after parsing (host/common/cmdline.hpp, docs/reliability.md).
#include <gtest/gtest.h>

#include <fcntl.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "cmdline.hpp"

namespace mc1::cmdline {
namespace {

class CmdlineFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    char tmpl[] = "/tmp/cmdline_files_test_XXXXXX";
    dir_ = mkdtemp(tmpl);
    std::ofstream(file("in.txt")) << "input\n";
    app_.add_option("--out", out_)->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    files_.input(app_.add_option("--in", in_), "the input");
    files_.output(app_.add_option("--stats", stats_));
    files_.output(app_.get_option("--out"), {".gtkw", ".kpc.txt"});
  }
  void TearDown() override { std::system(("rm -rf " + dir_).c_str()); }

  std::string file(const std::string& name) const { return dir_ + "/" + name; }

  // Parses `args` (after the program's name), then files_.check(); returns
  // its error, "" when it passed.
  std::string check(std::vector<std::string> args) {
    args.insert(args.begin(), "prog");
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    app_.parse(static_cast<int>(argv.size()), argv.data());
    try {
      files_.check();
      return "";
    } catch (const UsageError& e) {
      return e.what();
    }
  }

  std::string dir_;
  CLI::App app_;
  Files files_;
  std::string in_, out_, stats_;
};

TEST_F(CmdlineFiles, DistinctFilesPass) {
  EXPECT_EQ(check({"--in", file("in.txt"), "--out", file("a.fst"), "--stats", file("s.json")}), "");
  EXPECT_EQ(files_.outputs().size(), 4u) << "--stats, --out and its two side files";
}

TEST_F(CmdlineFiles, OutputOnAnInputThroughASymbolicLink) {
  ASSERT_EQ(symlink("in.txt", file("sym.txt").c_str()), 0);
  EXPECT_EQ(check({"--in", file("in.txt"), "--stats", file("sym.txt")}),
            "--stats " + file("sym.txt") + " would replace the input " + file("in.txt"));
}

TEST_F(CmdlineFiles, OutputOnAnInputThroughAHardLink) {
  ASSERT_EQ(link(file("in.txt").c_str(), file("hard.txt").c_str()), 0);
  EXPECT_EQ(check({"--in", file("hard.txt"), "--out", file("in.txt")}),
            "--out " + file("in.txt") + " would replace the input " + file("hard.txt"));
}

TEST_F(CmdlineFiles, SideFileOnAnotherOutput) {
  EXPECT_EQ(check({"--out", file("a.fst"), "--stats", file("./a.fst.kpc.txt")}),
            "--stats and --out's side file name one file: " + file("a.fst.kpc.txt"));
}

TEST_F(CmdlineFiles, OutputGivenTwice) {
  EXPECT_EQ(check({"--out", file("a.fst"), "--out", file("b.fst")}),
            "--out is given 2 times (" + file("a.fst") + ", " + file("b.fst") +
                "): the last would replace the others; name one file");
}

TEST_F(CmdlineFiles, UnwritableOutputFoundBeforeTheRun) {
  const std::string err = check({"--stats", file("none/s.json")});
  EXPECT_EQ(err.rfind("--stats: " + file("none/s.json") + ": cannot open for writing: ", 0), 0u) << err;
}

TEST_F(CmdlineFiles, AddedPathsAndStandardInput) {
  files_.add_output("--out-dir", file("in.txt"));
  EXPECT_EQ(check({"--in", file("in.txt")}), "--out-dir " + file("in.txt") + " would replace the input " + file("in.txt"));
  // A regular file redirected to standard input is an input.
  Files f;
  f.reads_stdin();
  f.add_output("--trace", file("in.txt"));
  const int saved = dup(0);
  const int fd = open(file("in.txt").c_str(), O_RDONLY);
  ASSERT_GE(fd, 0);
  dup2(fd, 0);
  close(fd);
  EXPECT_THROW(f.check(), UsageError);
  dup2(saved, 0);
  close(saved);
}

TEST_F(CmdlineFiles, AnInputsFallbackWhenNotGiven) {
  Files f;
  CLI::App app;
  std::string scene, json;
  f.input(app.add_option("--scene", scene), "the scene", file("in.txt"));
  f.output(app.add_option("--json", json));
  char prog[] = "prog", opt[] = "--json";
  std::string out = file("in.txt");
  char* argv[] = {prog, opt, out.data()};
  app.parse(3, argv);
  EXPECT_THROW(f.check(), UsageError) << "--json on the default scene";
}

TEST_F(CmdlineFiles, ManyOutputsCheckedOnce) {
  for (int i = 0; i < 5000; ++i) files_.add_output("--out-dir", file("point-" + std::to_string(i) + ".json"));
  files_.add_output("--json", file("point-4321.json"));
  EXPECT_EQ(check({}), "--out-dir and --json name one file: " + file("point-4321.json"));
}

}  // namespace
}  // namespace mc1::cmdline
