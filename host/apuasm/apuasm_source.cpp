// Reading source files with POSIX calls, so that a directory (which opens and
// reads as an empty file through std::ifstream) and a read error are told
// apart from an empty source.
#include "apuasm_source.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "apuasm.hpp"

namespace mc1::apuasm::detail {
namespace {

// Closes the descriptor on every path out of read_source.
class Fd {
 public:
  explicit Fd(int fd) : fd_(fd) {}
  ~Fd() {
    if (fd_ >= 0) ::close(fd_);
  }
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

[[noreturn]] void fail_errno() { throw SourceError(std::strerror(errno)); }

[[noreturn]] void fail_too_large() {
  throw SourceError("larger than " + std::to_string(kMaxSourceBytes >> 20) + " MiB");
}

}  // namespace

std::string read_source(const std::string& path) {
  const Fd fd(::open(path.c_str(), O_RDONLY | O_CLOEXEC));
  if (fd.get() < 0) fail_errno();
  struct stat st {};
  if (::fstat(fd.get(), &st) != 0) fail_errno();
  if (S_ISDIR(st.st_mode)) throw SourceError("is a directory");
  std::string text;
  if (S_ISREG(st.st_mode)) {
    if (static_cast<std::uint64_t>(st.st_size) > kMaxSourceBytes) fail_too_large();
    text.reserve(static_cast<size_t>(st.st_size));
  }
  char buf[65536];
  // A device or a FIFO may never end: at most one byte over the limit is read.
  while (text.size() <= kMaxSourceBytes) {
    const size_t want = std::min(sizeof buf, kMaxSourceBytes + 1 - text.size());
    const ssize_t n = ::read(fd.get(), buf, want);
    if (n == 0) return text;
    if (n < 0) {
      if (errno == EINTR) continue;
      fail_errno();
    }
    text.append(buf, static_cast<size_t>(n));
  }
  fail_too_large();
}

std::string include_path(const std::string& from_file, const std::string& name) {
  if (!name.empty() && name[0] == '/') return name;
  const auto slash = from_file.find_last_of('/');
  return (slash == std::string::npos ? "" : from_file.substr(0, slash + 1)) + name;
}

}  // namespace mc1::apuasm::detail
