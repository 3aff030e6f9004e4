// Reading source files with POSIX calls, so that a directory (which opens and
// reads as an empty file through std::ifstream) and a read error are told
// apart from an empty source.
#include "apuasm_source.hpp"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

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

}  // namespace

std::string read_source(const std::string& path) {
  const Fd fd(::open(path.c_str(), O_RDONLY | O_CLOEXEC));
  if (fd.get() < 0) fail_errno();
  struct stat st {};
  if (::fstat(fd.get(), &st) != 0) fail_errno();
  if (S_ISDIR(st.st_mode)) throw SourceError("is a directory");
  std::string text;
  char buf[65536];
  for (;;) {
    const ssize_t n = ::read(fd.get(), buf, sizeof buf);
    if (n == 0) return text;
    if (n < 0) {
      if (errno == EINTR) continue;
      fail_errno();
    }
    text.append(buf, static_cast<size_t>(n));
  }
}

std::string include_path(const std::string& from_file, const std::string& name) {
  if (!name.empty() && name[0] == '/') return name;
  const auto slash = from_file.find_last_of('/');
  return (slash == std::string::npos ? "" : from_file.substr(0, slash + 1)) + name;
}

}  // namespace mc1::apuasm::detail
