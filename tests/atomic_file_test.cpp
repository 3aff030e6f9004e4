// Output files that appear whole or not at all (host/common/atomic_file).
#include <gtest/gtest.h>

#include <csignal>
#include <cstdint>
#include <cstdio>
#include <dirent.h>
#include <fstream>
#include <iterator>
#include <list>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <utility>
#include <vector>

#include "atomic_file.hpp"

namespace mc1 {
namespace {

// A scratch directory, emptied and removed at the end.
class ScratchDir {
 public:
  ScratchDir() {
    char tmpl[] = "/tmp/atomic_file_test_XXXXXX";
    path_ = mkdtemp(tmpl);
  }
  ~ScratchDir() {
    for (const auto& n : names()) std::remove((path_ + "/" + n).c_str());
    rmdir(path_.c_str());
  }
  std::set<std::string> names() const {
    std::set<std::string> out;
    DIR* d = opendir(path_.c_str());
    while (const dirent* e = d ? readdir(d) : nullptr)
      if (std::string(e->d_name) != "." && std::string(e->d_name) != "..") out.insert(e->d_name);
    if (d) closedir(d);
    return out;
  }
  std::string file(const std::string& name) const { return path_ + "/" + name; }

 private:
  std::string path_;
};

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

mode_t mode_of(const std::string& path) {
  struct stat st {};
  stat(path.c_str(), &st);
  return st.st_mode;
}

// Files may grow to `bytes` only, while it lives: a write beyond fails with
// EFBIG (SIGXFSZ ignored), a disk that fills up in the middle of a file.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    getrlimit(RLIMIT_FSIZE, &saved_);
    old_handler_ = std::signal(SIGXFSZ, SIG_IGN);
    rlimit lim = saved_;
    lim.rlim_cur = bytes;
    setrlimit(RLIMIT_FSIZE, &lim);
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &saved_);
    std::signal(SIGXFSZ, old_handler_);
  }

 private:
  rlimit saved_{};
  void (*old_handler_)(int) = nullptr;
};

TEST(AtomicFile, GoodWriteRenamesIntoPlace) {
  ScratchDir dir;
  const std::string path = dir.file("out.bin");
  const mode_t old_mask = umask(027);
  write_file_atomically(path, "first");
  umask(old_mask);
  EXPECT_EQ(slurp(path), "first");
  EXPECT_EQ(mode_of(path) & 07777, 0640u) << "a new file gets 0666 less the umask, as from open(2)";
  chmod(path.c_str(), 0604);
  EXPECT_EQ(dir.names(), std::set<std::string>{"out.bin"});
  write_file_atomically(path, std::string("second\0bytes", 12));
  EXPECT_EQ(slurp(path), std::string("second\0bytes", 12));
  EXPECT_EQ(mode_of(path) & 07777, 0604u) << "an existing file keeps its mode";
  EXPECT_EQ(dir.names(), std::set<std::string>{"out.bin"});
}

TEST(AtomicFile, StagedFilesAppearOnlyOnCommit) {
  ScratchDir dir;
  {
    StagedFile a(dir.file("a"), "A");
    EXPECT_EQ(dir.names().count("a"), 0u);
    EXPECT_EQ(dir.names().size(), 1u);  // the temporary file
  }
  EXPECT_TRUE(dir.names().empty()) << "an uncommitted file is removed";
  StagedFile a(dir.file("a"), "A");
  StagedFile b(std::move(a));
  b.commit();
  EXPECT_EQ(slurp(dir.file("a")), "A");
  EXPECT_EQ(dir.names(), std::set<std::string>{"a"});
}

TEST(AtomicFile, WriteToDevFullThrows) {
  try {
    write_file_atomically("/dev/full", "x");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "/dev/full: cannot write: No space left on device");
  }
  struct stat st {};
  ASSERT_EQ(stat("/dev/full", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode)) << "the device must be written, never replaced";
  write_file_atomically("/dev/null", "x");  // devices that take the bytes are fine
  EXPECT_TRUE(S_ISCHR(mode_of("/dev/null")));
}

TEST(AtomicFile, FailedWriteLeavesNoFile) {
  ScratchDir dir;
  const std::string big(4096, 'x');
  {
    FileSizeLimit limit(100);
    EXPECT_THROW(write_file_atomically(dir.file("new.bin"), big), std::runtime_error);
  }
  EXPECT_TRUE(dir.names().empty()) << "neither the file nor its temporary file may remain";

  write_file_atomically(dir.file("old.bin"), "old");
  {
    FileSizeLimit limit(100);
    EXPECT_THROW(write_file_atomically(dir.file("old.bin"), big), std::runtime_error);
  }
  EXPECT_EQ(slurp(dir.file("old.bin")), "old") << "a failed write leaves the old file as it was";
  EXPECT_EQ(dir.names(), std::set<std::string>{"old.bin"});
}

TEST(AtomicFile, ErrorsNameThePath) {
  ScratchDir dir;
  try {
    write_file_atomically(dir.file("no/such/x.bin"), "x");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()),
              dir.file("no/such/x.bin") + ": cannot create a temporary file beside it: No such file or directory");
  }
  mkdir(dir.file("d").c_str(), 0700);
  try {
    write_file_atomically(dir.file("d"), "x");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), dir.file("d") + ": is a directory");
  }
  rmdir(dir.file("d").c_str());
}

TEST(AtomicFile, WritesThroughASymbolicLink) {
  ScratchDir dir;
  write_file_atomically(dir.file("real"), "old");
  ASSERT_EQ(symlink("real", dir.file("link").c_str()), 0);
  write_file_atomically(dir.file("link"), "new");
  EXPECT_EQ(slurp(dir.file("real")), "new");
  struct stat st {};
  ASSERT_EQ(lstat(dir.file("link").c_str(), &st), 0);
  EXPECT_TRUE(S_ISLNK(st.st_mode)) << "the link stays a link";
}

// A writer that opens its file by name, as the FST writer does: it unlinks
// the name and creates the file anew.
void write_as_library(const std::string& path, const std::string& text) {
  std::remove(path.c_str());
  std::ofstream(path, std::ios::binary) << text;
}

// The sections of an FST file as its writer frames them (a type byte, a
// big-endian 64-bit length that counts itself): a header, a value-change
// block, the geometry and the hierarchy.
std::string fst_sections() {
  std::string out;
  for (auto [type, length] : {std::pair{0, 329}, {8, 40}, {3, 8}, {6, 20}}) {
    out += static_cast<char>(type);
    for (int i = 7; i >= 0; --i) out += static_cast<char>((std::uint64_t(length) >> (8 * i)) & 0xff);
    out.append(static_cast<std::size_t>(length - 8), 'x');
  }
  return out;
}

TEST(AtomicFile, ForWriterRenamesTheWritersFileOnCommit) {
  ScratchDir dir;
  write_file_atomically(dir.file("t.fst"), "old");
  chmod(dir.file("t.fst").c_str(), 0640);
  StagedFile f = StagedFile::for_writer(dir.file("t.fst"));
  EXPECT_EQ(dir.names().size(), 2u) << "the temporary file is made at once";
  write_as_library(f.temp(), fst_sections());
  EXPECT_EQ(slurp(dir.file("t.fst")), "old") << "untouched until commit()";
  f.commit();
  EXPECT_EQ(slurp(dir.file("t.fst")), fst_sections());
  EXPECT_EQ(mode_of(dir.file("t.fst")) & 0777, 0640u) << "a replaced file keeps its mode";
  EXPECT_EQ(dir.names(), std::set<std::string>{"t.fst"});
}

// An FST writer reports no failed write: a file cut short (a full disk) or
// without its closing sections is removed by commit(), which throws, and
// the old file stays.
TEST(AtomicFile, ForWriterFstNotWholeIsNotCommitted) {
  ScratchDir dir;
  write_file_atomically(dir.file("t.fst"), "old");
  const std::string whole = fst_sections();
  for (const std::string& bad : {whole.substr(0, whole.size() - 3), whole.substr(0, 330 + 40 + 1), std::string()}) {
    StagedFile f = StagedFile::for_writer(dir.file("t.fst"));
    write_as_library(f.temp(), bad);
    try {
      f.commit();
      ADD_FAILURE() << "an FST of " << bad.size() << " bytes was committed";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("t.fst: the waveform was not written whole"), std::string::npos)
          << e.what();
    }
    EXPECT_EQ(dir.names(), std::set<std::string>{"t.fst"});
    EXPECT_EQ(slurp(dir.file("t.fst")), "old");
  }
}

TEST(AtomicFile, ForWriterWithoutCommitLeavesNothing) {
  ScratchDir dir;
  {
    StagedFile f = StagedFile::for_writer(dir.file("t.vcd"), ".vcd");
    EXPECT_EQ(f.temp().substr(f.temp().size() - 4), ".vcd");
    write_as_library(f.temp(), "half a waveform");
  }
  EXPECT_TRUE(dir.names().empty());
}

TEST(AtomicFile, ForWriterRefusesWhatTheWriterWouldReplace) {
  ScratchDir dir;
  ASSERT_EQ(mkdir(dir.file("d").c_str(), 0755), 0);
  try {
    StagedFile::for_writer(dir.file("d"));
    ADD_FAILURE() << "a directory was taken";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), dir.file("d") + ": is a directory");
  }
  rmdir(dir.file("d").c_str());
  try {
    StagedFile::for_writer("/dev/null");  // refused before anything is opened
    ADD_FAILURE() << "a device was taken";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "/dev/null: is not a regular file");
  }
  try {
    StagedFile::for_writer(dir.file("none/t.fst"));
    ADD_FAILURE() << "a missing directory was taken";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()),
              dir.file("none/t.fst") + ": cannot create a temporary file beside it: No such file or directory");
  }
  EXPECT_TRUE(dir.names().empty());
}

TEST(AtomicFile, SameFileSeesThroughLinksAndDots) {
  ScratchDir dir;
  write_file_atomically(dir.file("real"), "x");
  ASSERT_EQ(symlink("real", dir.file("link").c_str()), 0);
  EXPECT_TRUE(same_file(dir.file("link"), dir.file("real")));
  EXPECT_TRUE(same_file(dir.file("link"), dir.file("./real")));
  EXPECT_FALSE(same_file(dir.file("link"), dir.file("other")));
  EXPECT_TRUE(same_file(dir.file("new"), dir.file("../") + dir.file("new").substr(5))) << "a file not made yet";
  EXPECT_FALSE(same_file(dir.file("new"), dir.file("real")));
  ASSERT_EQ(link(dir.file("real").c_str(), dir.file("hard").c_str()), 0);
  EXPECT_TRUE(same_file(dir.file("hard"), dir.file("real"))) << "a hard link";
  EXPECT_FALSE(same_file("/dev/null", "/dev/./null")) << "a device is written in place, by each output";
}

// A program stopped by a signal leaves none of its temporary files (nor an
// FST writer's ".hier" beside one); an ignored signal stays ignored.
TEST(AtomicFile, SignalRemovesStagedFiles) {
  ScratchDir dir;
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    signal(SIGHUP, SIG_IGN);
    remove_staged_files_on_signals();
    StagedFile a(dir.file("a.png"), "half");
    StagedFile w = StagedFile::for_writer(dir.file("t.fst"));
    std::ofstream(w.temp() + ".hier") << "hierarchy";
    raise(SIGHUP);  // ignored: the program goes on
    if (dir.names().size() != 3) _exit(3);
    raise(SIGTERM);
    _exit(4);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status)) << "exit " << WEXITSTATUS(status);
  EXPECT_EQ(WTERMSIG(status), SIGTERM);
  EXPECT_TRUE(dir.names().empty()) << *dir.names().begin();
}

// However many files are staged at once, from however many threads, and
// however long their paths, a signal removes every one (the handler's list
// grows: blocks of 64 slots, path buffers from 256 bytes). Files staged and
// dropped before leave their slots to the later ones; committed files stay.
TEST(AtomicFile, SignalRemovesHundredsOfStagedFilesFromThreads) {
  ScratchDir dir;
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    remove_staged_files_on_signals();
    const std::string long_name(200, 'x');  // a temporary path over 256 bytes
    std::mutex m;
    std::list<StagedFile> staged;
    auto stage = [&](int thread, int count) {
      for (int i = 0; i < count; ++i) {
        const std::string name = std::to_string(thread) + "-" + std::to_string(i) + (i % 3 ? "" : long_name);
        StagedFile f(dir.file(name), "part");
        const std::lock_guard<std::mutex> lock(m);
        staged.push_back(std::move(f));
      }
    };
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t) threads.emplace_back(stage, t, 150);
    for (std::thread& t : threads) t.join();
    staged.erase(staged.begin(), std::next(staged.begin(), 300));  // their slots free again
    stage(4, 200);
    for (int i = 0; i < 5; ++i) StagedFile(dir.file("kept" + std::to_string(i)), "whole").commit();
    if (staged.size() != 500 || dir.names().size() != 505) _exit(3);
    raise(SIGTERM);
    _exit(4);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status)) << "exit " << WEXITSTATUS(status);
  EXPECT_EQ(WTERMSIG(status), SIGTERM);
  const std::set<std::string> kept{"kept0", "kept1", "kept2", "kept3", "kept4"};
  const std::set<std::string> left = dir.names();
  ASSERT_EQ(left.size(), kept.size()) << "files left, among them " << *left.begin();
  EXPECT_EQ(left, kept);
}

// SIGBUS (an FST writer's mapped file on a full disk): the staged files go,
// and the program exits 1 with a message instead of dumping core.
TEST(AtomicFile, SigbusRemovesStagedFilesAndExitsOne) {
  ScratchDir dir;
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    remove_staged_files_on_signals();
    StagedFile w = StagedFile::for_writer(dir.file("t.fst"));
    std::ofstream(w.temp() + ".hier") << "hierarchy";
    raise(SIGBUS);
    _exit(4);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status)) << "signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), 1);
  EXPECT_TRUE(dir.names().empty()) << *dir.names().begin();
}

TEST(AtomicFile, CheckDistinctFilesNamesBoth) {
  ScratchDir dir;
  write_file_atomically(dir.file("s.json"), "{}");
  const NamedPaths in{{"the scene", dir.file("s.json")}};
  EXPECT_NO_THROW(check_distinct_files(in, {{"--out", dir.file("a.png")}, {"--stats", dir.file("a.json")}}));
  EXPECT_NO_THROW(check_distinct_files(in, {{"--out", "/dev/null"}, {"--stats", "/dev/null"}}));
  try {
    check_distinct_files(in, {{"--out", dir.file("a.png")}, {"--stats", dir.file("./a.png")}});
    ADD_FAILURE() << "two outputs on one file";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "--out and --stats name one file: " + dir.file("./a.png"));
  }
  try {
    check_distinct_files(in, {{"--out", dir.file("s.json")}});
    ADD_FAILURE() << "an output on the input";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "--out " + dir.file("s.json") + " would replace the scene " + dir.file("s.json"));
  }
}

}  // namespace
}  // namespace mc1
