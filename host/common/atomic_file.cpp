// Staged output files (atomic_file.hpp). POSIX calls rather than streams: a
// std::ofstream reports neither which call failed nor why, and its
// destructor's close() (where a small file's write happens) not at all.
#include "atomic_file.hpp"

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <new>
#include <fcntl.h>
#include <stdexcept>
#include <string>
#include <sys/stat.h>
#include <unistd.h>
#include <utility>

namespace mc1 {
namespace {

[[noreturn]] void fail(const std::string& path, const char* what, int err) {
  throw std::runtime_error(path + ": " + what + ": " + std::strerror(err));
}

// Writes all of `bytes` to `fd` and closes it; false (errno set) on failure.
bool write_and_close(int fd, std::string_view bytes) {
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int err = n < 0 ? errno : EIO;
      ::close(fd);
      errno = err;
      return false;
    }
    done += static_cast<size_t>(n);
  }
  return ::close(fd) == 0;
}

std::string real_path(const std::string& path) {
  char* real = ::realpath(path.c_str(), nullptr);
  if (!real) return {};
  std::string out = real;
  std::free(real);
  return out;
}

// The target with symbolic links resolved, so that the rename replaces the
// file a link points to rather than the link. A file that does not exist
// yet: its directory resolved and its name (`path` itself if the directory
// does not resolve either).
std::string resolve(const std::string& path) {
  if (std::string real = real_path(path); !real.empty()) return real;
  const auto slash = path.find_last_of('/');
  const std::string dir = real_path(slash == std::string::npos ? "." : slash == 0 ? "/" : path.substr(0, slash));
  if (dir.empty()) return path;
  return (dir == "/" ? "" : dir) + "/" + (slash == std::string::npos ? path : path.substr(slash + 1));
}

// Creates "DIR.NAME.tmp.PID.N" + suffix exclusively (N counts up past names
// in use), with mode 0666 so that open(2) applies the umask as for any new
// file; returns the descriptor and sets `temp`, or -1 with errno set.
int create_temp(const std::string& target, std::string& temp, const std::string& suffix = "") {
  const auto slash = target.find_last_of('/');
  const std::string dir = slash == std::string::npos ? "" : target.substr(0, slash + 1);
  const std::string name = slash == std::string::npos ? target : target.substr(slash + 1);
  static std::atomic<unsigned> counter{0};
  for (int tries = 0; tries < 1000; ++tries) {
    temp = dir + "." + name + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++) + suffix;
    const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0 || errno != EEXIST) return fd;
  }
  return -1;
}

// The temporary files of the StagedFiles alive, for the signal handler
// (remove_staged_files_on_signals), which may neither lock nor allocate:
// blocks of slots in a list that only grows. A StagedFile takes a free slot
// (compare-and-swap); when every slot is taken, a new block is made under a
// lock, outside the handler, and linked in whole (release) before it is
// used, so the handler (acquire) walks every block there is. A slot keeps
// its path buffer: one is replaced only by a larger one (powers of two from
// 256 bytes), which links to the smaller (its first bytes), never freed, as
// the handler of another thread may be reading it. Memory: a few hundred
// bytes a slot for the usual paths, for as many slots as there were staged
// files alive at once; nothing is freed, nothing is lost.
constexpr std::size_t kBlockSlots = 64;
constexpr std::size_t kMinBuffer = 256;
struct Slot {
  std::atomic<bool> used{false};   // taken by a StagedFile
  std::atomic<bool> ready{false};  // `path` written whole: the handler may use it
  std::atomic<char*> path{nullptr};
  // Only the slot's owner reads or changes these: the buffer `path` is in,
  // after a link to the slot's previous buffer, and the bytes `path` has.
  char* buffer = nullptr;
  std::size_t capacity = 0;
};
struct Block {
  Slot slots[kBlockSlots];
  std::atomic<Block*> next{nullptr};
};
static_assert(std::atomic<Block*>::is_always_lock_free && std::atomic<char*>::is_always_lock_free &&
                  std::atomic<bool>::is_always_lock_free,
              "the signal handler reads these without a lock");
Block g_first_block;
std::mutex g_grow;  // one thread at a time appends a block

// A free slot of the blocks, taken; nullptr when all are in use.
Slot* take_free_slot() {
  for (Block* b = &g_first_block; b != nullptr; b = b->next.load(std::memory_order_acquire))
    for (Slot& s : b->slots) {
      bool expected = false;
      if (!s.used.load(std::memory_order_relaxed) &&
          s.used.compare_exchange_strong(expected, true, std::memory_order_acquire))
        return &s;
    }
  return nullptr;
}

// A slot for one more staged file: a free one, else one of a new block
// (nullptr if it cannot be made).
Slot* take_slot() {
  for (;;) {
    if (Slot* s = take_free_slot()) return s;
    const std::lock_guard<std::mutex> lock(g_grow);
    Block* last = &g_first_block;
    while (Block* next = last->next.load(std::memory_order_acquire)) last = next;
    if (Slot* s = take_free_slot()) return s;  // freed or appended meanwhile
    Block* block = new (std::nothrow) Block;
    if (block == nullptr) return nullptr;
    last->next.store(block, std::memory_order_release);
  }
}

// `temp` known to the handler; its slot. Every staged file gets one, of any
// length; nullptr only when memory runs out (the caller fails, ENOMEM).
Slot* register_temp(const std::string& temp) {
  Slot* s = take_slot();
  if (s == nullptr) return nullptr;
  const std::size_t need = temp.size() + 6;  // room for ".hier"
  if (s->capacity < need) {
    std::size_t size = kMinBuffer;
    while (size - sizeof(char*) < need) size *= 2;
    char* buffer = new (std::nothrow) char[size];
    if (buffer == nullptr) {
      s->used.store(false, std::memory_order_release);
      return nullptr;
    }
    std::memcpy(buffer, &s->buffer, sizeof(char*));  // the smaller one kept (above)
    s->buffer = buffer;
    s->capacity = size - sizeof(char*);
    s->path.store(buffer + sizeof(char*), std::memory_order_relaxed);
  }
  std::memcpy(s->path.load(std::memory_order_relaxed), temp.c_str(), temp.size() + 1);
  s->ready.store(true, std::memory_order_release);
  return s;
}

void unregister_temp(void*& slot) {
  if (slot == nullptr) return;
  Slot* s = static_cast<Slot*>(slot);
  s->ready.store(false, std::memory_order_release);
  s->used.store(false, std::memory_order_release);
  slot = nullptr;
}

extern "C" void remove_staged_and_reraise(int sig) {
  for (Block* b = &g_first_block; b != nullptr; b = b->next.load(std::memory_order_acquire))
    for (Slot& s : b->slots) {
      if (!s.ready.load(std::memory_order_acquire)) continue;
      char* path = s.path.load(std::memory_order_relaxed);
      ::unlink(path);
      const std::size_t n = std::strlen(path);
      std::memcpy(path + n, ".hier", 6);  // an FST writer's hierarchy, beside its file
      ::unlink(path);
      path[n] = '\0';
    }
  if (sig == SIGBUS) {
    // A page of a mapped file that the file system could not back: an FST
    // writer's on a full disk. The outputs are gone; the run failed.
    static const char kMessage[] =
        "error: a mapped output file could not be written (SIGBUS: is its file system full?); no output was kept\n";
    (void)!::write(STDERR_FILENO, kMessage, sizeof kMessage - 1);
    ::_exit(1);
  }
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}

// FST (GTKWave's format): sections of a type byte and a 64-bit big-endian
// length that counts itself, from the header to the end of the file; a
// writer adds the geometry and hierarchy sections when it closes. A write
// that failed (a full disk) leaves a section cut short or one missing.
// Returns what is wrong, or "" for a whole file.
std::string fst_incomplete(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return std::string("cannot open: ") + std::strerror(errno);
  struct stat st {};
  const off_t size = ::fstat(fd, &st) == 0 ? st.st_size : -1;
  constexpr unsigned char kHeader = 0, kGeometry = 3, kHier = 4, kHierLz4 = 6, kHierLz4Duo = 7;
  bool geometry = false, hierarchy = false;
  std::string why;
  off_t at = 0;
  for (int n = 0; why.empty() && at < size; ++n) {
    unsigned char head[9];
    if (::pread(fd, head, sizeof head, at) != static_cast<ssize_t>(sizeof head)) {
      why = "a section cut short at byte " + std::to_string(at);
      break;
    }
    std::uint64_t length = 0;
    for (int i = 1; i < 9; ++i) length = length << 8 | head[i];
    if ((n == 0 && head[0] != kHeader) || length < 8 || length > static_cast<std::uint64_t>(size - at - 1))
      why = "a section cut short at byte " + std::to_string(at);
    geometry |= head[0] == kGeometry;
    hierarchy |= head[0] == kHier || head[0] == kHierLz4 || head[0] == kHierLz4Duo;
    at += 1 + static_cast<off_t>(length);
  }
  ::close(fd);
  if (why.empty() && (size <= 0 || !geometry || !hierarchy)) why = "no geometry or hierarchy section";
  return why;
}

}  // namespace

void remove_staged_files_on_signals() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGBUS}) {
      struct sigaction old {};
      if (::sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
      struct sigaction act {};
      act.sa_handler = remove_staged_and_reraise;
      sigemptyset(&act.sa_mask);
      ::sigaction(sig, &act, nullptr);
    }
  });
}

StagedFile::StagedFile(const std::string& path, std::string_view bytes) : path_(path), target_(resolve(path)) {
  struct stat st {};
  const bool exists = ::stat(target_.c_str(), &st) == 0;
  if (exists && S_ISDIR(st.st_mode)) throw std::runtime_error(path_ + ": is a directory");
  if (exists && !S_ISREG(st.st_mode)) {
    const int fd = ::open(target_.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd < 0) fail(path_, "cannot open", errno);
    if (!write_and_close(fd, bytes)) fail(path_, "cannot write", errno);
    return;
  }
  std::string temp;
  const int fd = create_temp(target_, temp);
  if (fd < 0) fail(path_, "cannot create a temporary file beside it", errno);
  // Known to the signal handler before it is written: a signal in a long
  // write removes it too.
  slot_ = register_temp(temp);
  if (slot_ == nullptr) {
    ::close(fd);
    ::unlink(temp.c_str());
    fail(path_, "cannot register its temporary file for removal on a signal", ENOMEM);
  }
  // A replaced file keeps its mode.
  if ((exists && ::fchmod(fd, st.st_mode & 07777) != 0) || !write_and_close(fd, bytes)) {
    const int err = errno;
    ::unlink(temp.c_str());
    unregister_temp(slot_);
    fail(path_, "cannot write", err);
  }
  temp_ = std::move(temp);
}

StagedFile::StagedFile(const std::string& path) : path_(path), target_(resolve(path)) {}

StagedFile StagedFile::for_writer(const std::string& path, const std::string& suffix) {
  StagedFile f(path);
  struct stat st {};
  if (::stat(f.target_.c_str(), &st) == 0) {
    if (S_ISDIR(st.st_mode)) throw std::runtime_error(path + ": is a directory");
    if (!S_ISREG(st.st_mode)) throw std::runtime_error(path + ": is not a regular file");
    f.mode_ = st.st_mode & 07777;
  }
  // Created (and closed) here, so that the name is this file's and the
  // directory is known to take it; the writer then replaces it.
  std::string temp;
  const int fd = create_temp(f.target_, temp, suffix);
  if (fd < 0) fail(path, "cannot create a temporary file beside it", errno);
  ::close(fd);
  f.slot_ = register_temp(temp);
  if (f.slot_ == nullptr) {
    ::unlink(temp.c_str());
    fail(path, "cannot register its temporary file for removal on a signal", ENOMEM);
  }
  f.temp_ = std::move(temp);
  f.writer_ = true;
  return f;
}

StagedFile::StagedFile(StagedFile&& other) noexcept
    : path_(std::move(other.path_)),
      target_(std::move(other.target_)),
      temp_(std::exchange(other.temp_, {})),
      mode_(other.mode_),
      slot_(std::exchange(other.slot_, nullptr)),
      writer_(other.writer_) {}

bool same_file(const std::string& a, const std::string& b) {
  struct stat sa {};
  struct stat sb {};
  if (::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0)
    return S_ISREG(sa.st_mode) && sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
  return resolve(a) == resolve(b);
}

void check_writable(const std::string& path) {
  std::string why;
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode)) {
    if (::access(path.c_str(), W_OK) == 0) return;
    why = std::strerror(errno);
  } else {
    try {
      const StagedFile probe(path, "");  // never committed: its destructor removes it
      return;
    } catch (const std::runtime_error& e) {
      why = e.what();  // "PATH: what failed: reason"
      if (why.rfind(path + ": ", 0) == 0) why.erase(0, path.size() + 2);
    }
  }
  throw std::runtime_error(path + ": cannot open for writing: " + why);
}

namespace {

// What same_file compares, for one path: "i" device and inode of a regular
// file that exists, "p" the resolved path of one that does not; "" (equal
// to nothing) for a directory, device or FIFO.
std::string file_key(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0)
    return S_ISREG(st.st_mode) ? "i" + std::to_string(st.st_dev) + ":" + std::to_string(st.st_ino) : "";
  return "p" + resolve(path);
}

}  // namespace

// Each path's key once, looked up: a sweep declares thousands of outputs.
void check_distinct_files(const NamedPaths& inputs, const NamedPaths& outputs) {
  std::map<std::string, const std::pair<std::string, std::string>*> read, written;
  for (const auto& in : inputs)
    if (std::string key = file_key(in.second); !key.empty()) read.emplace(std::move(key), &in);
  for (const auto& out : outputs) {
    const auto& [option, path] = out;
    const std::string key = file_key(path);
    if (key.empty()) continue;
    if (const auto w = written.find(key); w != written.end())
      throw std::runtime_error(w->second->first + " and " + option + " name one file: " + path);
    if (const auto r = read.find(key); r != read.end())
      throw std::runtime_error(option + " " + path + " would replace " + r->second->first + " " + r->second->second);
    written.emplace(key, &out);
  }
}

StagedFile::~StagedFile() {
  if (!temp_.empty()) ::unlink(temp_.c_str());
  unregister_temp(slot_);
}

void StagedFile::commit() {
  if (temp_.empty()) return;
  // A waveform writer reports no failed write (a full disk): what it left
  // is checked whole before it replaces anything.
  if (writer_ && target_.size() > 4 && target_.compare(target_.size() - 4, 4, ".fst") == 0) {
    if (const std::string why = fst_incomplete(temp_); !why.empty()) {
      ::unlink(temp_.c_str());
      temp_.clear();
      unregister_temp(slot_);
      throw std::runtime_error(path_ + ": the waveform was not written whole (" + why +
                               "; is the file system full?)");
    }
  }
  if (mode_) ::chmod(temp_.c_str(), mode_);  // a replaced file keeps its mode
  const bool renamed = ::rename(temp_.c_str(), target_.c_str()) == 0;
  const int err = errno;
  if (!renamed) ::unlink(temp_.c_str());
  temp_.clear();
  unregister_temp(slot_);
  if (!renamed) fail(path_, "cannot rename the temporary file onto it", err);
}

void write_file_atomically(const std::string& path, std::string_view bytes) { StagedFile(path, bytes).commit(); }

}  // namespace mc1
