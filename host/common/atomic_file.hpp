// Output files that appear whole or not at all. A program that writes with
// these either leaves its complete output or, on any error (disk full, a
// write or close that fails), leaves nothing and reports the file and reason.
#pragma once

#include <string>
#include <string_view>
#include <sys/types.h>
#include <utility>
#include <vector>

namespace mc1 {

// `bytes` written beside `path` under a temporary name (".NAME.tmp.PID.N"),
// every write and the close checked; commit() renames it onto `path`. Until
// then `path` is untouched, and a StagedFile destroyed without commit()
// removes its temporary file, so several outputs can be staged first and
// committed only when all of them were written.
//
// A target that exists and is not a regular file (/dev/null, /dev/full, a
// FIFO) is written in place by the constructor, because renaming over it
// would replace the device; its write errors are reported all the same.
// Errors: std::runtime_error "PATH: what failed: reason". There is no fsync:
// this guards against writes that fail, not against a machine that crashes.
class StagedFile {
 public:
  StagedFile(const std::string& path, std::string_view bytes);
  StagedFile(StagedFile&& other) noexcept;
  StagedFile& operator=(StagedFile&&) = delete;
  StagedFile(const StagedFile&) = delete;
  StagedFile& operator=(const StagedFile&) = delete;
  ~StagedFile();

  // A file that another writer makes by name (a waveform library that opens,
  // and may first unlink, the file itself): it writes temp(), which ends in
  // `suffix` (the writer's own ending, for one that appends it: SystemC's
  // ".vcd"), and commit() renames temp() onto `path` as above. A target that
  // exists and is not a regular file is refused ("PATH: is not a regular
  // file"), as the writer would replace it, and so is a directory.
  static StagedFile for_writer(const std::string& path, const std::string& suffix = "");
  const std::string& temp() const { return temp_; }

  // Renames the staged file onto the target. A writer's FST that is not
  // whole (a write that failed on a full disk, which the writer does not
  // report) is removed instead: std::runtime_error "PATH: the waveform was
  // not written whole (...)".
  void commit();
  const std::string& path() const { return path_; }

 private:
  explicit StagedFile(const std::string& path);
  std::string path_;    // as the caller named it, for messages
  std::string target_;  // path_ with symbolic links resolved
  std::string temp_;    // the staged file; empty once committed or when written in place
  mode_t mode_ = 0;     // for_writer: the replaced file's mode (0: none)
  void* slot_ = nullptr;  // the signal handler's entry for temp_ (remove_staged_files_on_signals)
  bool writer_ = false;  // for_writer: commit() checks an FST is whole first
};

// StagedFile(path, bytes).commit().
void write_file_atomically(const std::string& path, std::string_view bytes);

// For a program (never a library: a host such as Python keeps its own
// handlers): SIGINT, SIGTERM and SIGHUP first remove the temporary files of
// the StagedFiles alive (and, for a writer's, the ".hier" file an FST writer
// keeps beside it), then end the program as the signal would have. A signal
// the program ignores stays ignored. Calling it again does nothing.
// SIGBUS (a mapped file the file system cannot back: an FST writer's on a
// full disk) removes them too, says so on stderr and exits 1.
void remove_staged_files_on_signals();

// Whether `a` and `b` name one regular file: the same device and inode when
// both exist (hard and symbolic links alike), else the same path with
// symbolic links, "." and ".." resolved (a file not made yet in its
// directory). Two names of a device or FIFO (/dev/null) are not: it is
// written in place, and one output does not replace the other.
bool same_file(const std::string& a, const std::string& b);

// Whether `path` can be written later, found now without touching what is
// there: a temporary file is staged beside it and dropped; a device or FIFO,
// which would be written in place, is checked for access only (opening a
// FIFO would wait for, and end, its reader). Throws std::runtime_error
// "PATH: cannot open for writing: reason" if not. For a run that writes its
// outputs at the end: a bad path fails before the work, not after it.
void check_writable(const std::string& path);

// (option or role, path) pairs.
using NamedPaths = std::vector<std::pair<std::string, std::string>>;
// Before a run: throws std::runtime_error if two outputs name one file
// ("-o and -l name one file: y.bin") or an output names an input ("--out
// s.json would replace the scene s.json"), so that no output is lost or
// replaces what the run reads.
void check_distinct_files(const NamedPaths& inputs, const NamedPaths& outputs);

}  // namespace mc1
