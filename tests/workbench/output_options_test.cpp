// cmdline::Files::outputs_each: an output option given more than once, each
// value a file of its own (mc1 render --profile p.md --profile p.json), is
// not refused as repeated; its files are still checked against each other,
// the inputs and the other outputs (host/common/cmdline.hpp).
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "cmdline.hpp"

namespace mc1::cmdline {
namespace {

class OutputsEach : public ::testing::Test {
 protected:
  void SetUp() override {
    char tmpl[] = "/tmp/output_options_test_XXXXXX";
    dir_ = mkdtemp(tmpl);
    std::ofstream(file("in.txt")) << "input\n";
    files_.input(app_.add_option("--in", in_), "the input");
    files_.outputs_each(app_.add_option("--profile", profiles_)->multi_option_policy(CLI::MultiOptionPolicy::TakeAll));
    files_.output(app_.add_option("--stats", stats_)->multi_option_policy(CLI::MultiOptionPolicy::TakeLast));
  }
  void TearDown() override { std::system(("rm -rf " + dir_).c_str()); }
  std::string file(const std::string& name) const { return dir_ + "/" + name; }

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

  std::string dir_, in_;
  CLI::App app_;
  Files files_;
  std::vector<std::string> profiles_;
  std::string stats_;
};

TEST_F(OutputsEach, EveryValueIsAnOutput) {
  EXPECT_EQ(check({"--profile", file("p.md"), "--profile", file("p.json"), "--stats", file("s.json")}), "");
  EXPECT_EQ(files_.outputs().size(), 3u);
}

TEST_F(OutputsEach, OneFileTwiceIsRefused) {
  EXPECT_EQ(check({"--profile", file("p.md"), "--profile", file("./p.md")}),
            "--profile and --profile name one file: " + file("./p.md"));
}

TEST_F(OutputsEach, AValueOnAnInputOrAnotherOutputIsRefused) {
  EXPECT_EQ(check({"--in", file("in.txt"), "--profile", file("p.md"), "--profile", file("in.txt")}),
            "--profile " + file("in.txt") + " would replace the input " + file("in.txt"));
}

TEST_F(OutputsEach, AnOrdinaryOutputGivenTwiceIsStillRefused) {
  EXPECT_EQ(check({"--profile", file("p.md"), "--stats", file("a.json"), "--stats", file("b.json")}),
            "--stats is given 2 times (" + file("a.json") + ", " + file("b.json") +
                "): the last would replace the others; name one file");
}

}  // namespace
}  // namespace mc1::cmdline
