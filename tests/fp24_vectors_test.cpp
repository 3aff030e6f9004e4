// The vector and golden readers of tb/fp24_vectors.cpp (fp24-run, its
// --check): a line longer than 4096 bytes is refused naming source:line,
// after reading no more than the limit, so a stream that never ends
// (/dev/zero, a FIFO) is not held whole.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

#include "fp24_vectors.hpp"

using namespace mc1::fp24;
using namespace mc1::fp24::tb;

namespace {

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const VectorError& e) {
    return e.what();
  }
  return "(no error)";
}

// A comment line of `bytes` bytes, the newline not counted.
std::string comment(std::size_t bytes) { return "#" + std::string(bytes - 1, 'x') + "\n"; }

}  // namespace

TEST(Fp24Vectors, GoldenLineOf4096BytesTakenLongerRefused) {
  std::istringstream fits("add 3f0000 3f0000 400000 00\n" + comment(4096) + "neg 3f0000 bf0000 00");
  const std::vector<Golden> g = read_golden(fits, "g.txt");
  ASSERT_EQ(g.size(), 2u);
  EXPECT_EQ(g[1].line, 3);
  EXPECT_EQ(g[1].expected.value, 0xBF0000u);
  std::istringstream too_long("add 3f0000 3f0000 400000 00\n" + comment(4097) + "neg 3f0000 bf0000 00\n");
  EXPECT_EQ(error_of([&] { read_golden(too_long, "g.txt"); }),
            "g.txt:2: line longer than 4096 bytes (not a vector file?)");
}

TEST(Fp24Vectors, VectorLineLongerThan4096BytesRefused) {
  std::istringstream fits(comment(4096) + "neg 3f0000");
  const std::vector<Issue> v = read_vectors(fits, "<stdin>");
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v[0].a, 0x3F0000u);
  std::istringstream too_long("neg 3f0000\n" + comment(4097));
  EXPECT_EQ(error_of([&] { read_vectors(too_long, "<stdin>"); }),
            "<stdin>:2: line longer than 4096 bytes (not a vector file?)");
}

// A file of NULs and no newline, as /dev/zero: refused at line 1 with 4096
// bytes read, not the whole megabyte.
TEST(Fp24Vectors, GoldenFileWithoutNewlinesRefusedAtTheLimit) {
  const std::string path = ::testing::TempDir() + "fp24_vectors_test_zeros.golden";
  std::ofstream(path, std::ios::binary | std::ios::trunc).close();
  std::filesystem::resize_file(path, std::uintmax_t{1} << 20);
  std::ifstream in(path, std::ios::binary);
  EXPECT_EQ(error_of([&] { read_golden(in, path); }), path + ":1: line longer than 4096 bytes (not a vector file?)");
  in.clear();
  EXPECT_EQ(in.tellg(), std::streampos(4096));
  std::remove(path.c_str());
}
