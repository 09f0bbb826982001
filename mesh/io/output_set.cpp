#include <metrica/error.hpp>
#include <metrica/io/atomic_file.hpp>
#include <metrica/io/output_set.hpp>

#include <fmt/core.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <limits.h>
#include <mutex>
#include <pthread.h>
#include <sys/stat.h>
#include <unistd.h>

namespace metrica::io {

namespace {

// Live temporaries for the signal handler: a list that only grows, pushed
// lock-free, read without locks (async-signal-safe); a removed entry is
// only marked dead.
struct TempNode {
  std::atomic<bool> live{true};
  TempNode* next = nullptr;
  char path[PATH_MAX] = {};
};
std::atomic<TempNode*> temp_head{nullptr};
std::mutex temp_mutex;  // registration and removal (never in the handler)

extern "C" void remove_temporaries_and_reraise(int sig) {
  for (TempNode* n = temp_head.load(std::memory_order_acquire); n; n = n->next)
    if (n->live.load(std::memory_order_acquire)) ::unlink(n->path);
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

void install_handlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
      struct sigaction old {};
      ::sigaction(sig, nullptr, &old);
      if (old.sa_handler == SIG_IGN) continue;  // e.g. nohup: keep ignoring
      struct sigaction sa {};
      sa.sa_handler = remove_temporaries_and_reraise;
      sigemptyset(&sa.sa_mask);
      ::sigaction(sig, &sa, nullptr);
    }
  });
}

OutputSet* open_set = nullptr;
std::mutex set_mutex;

void register_temporary(const std::string& path) {
  if (path.size() >= PATH_MAX) return;
  std::lock_guard lock(temp_mutex);
  for (TempNode* n = temp_head.load(); n; n = n->next)
    if (!n->live.load()) {  // reuse a dead entry: write the name, then mark live
      std::memcpy(n->path, path.c_str(), path.size() + 1);
      n->live.store(true, std::memory_order_release);
      return;
    }
  auto* node = new TempNode;
  std::memcpy(node->path, path.c_str(), path.size() + 1);
  node->next = temp_head.load();
  temp_head.store(node, std::memory_order_release);
}

}  // namespace

int create_temporary(const std::string& folder, std::string& path) {
  install_handlers();
  sigset_t held, old;
  sigemptyset(&held);
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&held, sig);
  ::pthread_sigmask(SIG_BLOCK, &held, &old);
  path = folder + "/.metrica-XXXXXX";
  const int fd = ::mkstemp(path.data());
  const int err = errno;
  if (fd >= 0) register_temporary(path);
  ::pthread_sigmask(SIG_SETMASK, &old, nullptr);
  errno = err;
  return fd;
}

void unregister_temporary(const std::string& path) {
  std::lock_guard lock(temp_mutex);
  for (TempNode* n = temp_head.load(); n; n = n->next)
    if (n->live.load() && path == n->path) {
      n->live.store(false, std::memory_order_release);
      return;
    }
}

std::string folder_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}

std::string writable_target(const std::string& path) {
  if (path.empty()) throw IoError("an output file name is empty");
  if (is_standard_output(path)) return path;
  std::string target = path;
  struct stat st {};
  // Follow symlinks (at most 40, as the kernel does): the link stays, its
  // target is replaced.
  for (int hops = 0; ::lstat(target.c_str(), &st) == 0 && S_ISLNK(st.st_mode); ++hops) {
    if (hops == 40) throw IoError(fmt::format("{}: too many levels of symbolic links", path));
    char buf[PATH_MAX];
    const ssize_t n = ::readlink(target.c_str(), buf, sizeof buf - 1);
    if (n < 0) throw IoError(fmt::format("{}: cannot read the symbolic link: {}", path, std::strerror(errno)));
    const std::string link(buf, static_cast<std::size_t>(n));
    target = link.front() == '/' ? link : folder_of(target) + "/" + link;
  }
  if (::lstat(target.c_str(), &st) == 0) {
    if (S_ISDIR(st.st_mode)) throw IoError(fmt::format("{}: is a folder, not a file", path));
    if (!S_ISREG(st.st_mode))
      throw IoError(fmt::format("{}: is not a regular file (a FIFO, device or socket): refusing to replace it", path));
    if ((st.st_mode & 0222) == 0 || ::access(target.c_str(), W_OK) != 0)
      throw IoError(fmt::format("{}: is read-only: refusing to replace it", path));
  } else if (errno != ENOENT) {
    throw IoError(fmt::format("{}: {}", path, std::strerror(errno)));
  }
  const std::string folder = folder_of(target);
  struct stat fs {};
  if (::stat(folder.c_str(), &fs) != 0)
    throw IoError(fmt::format("{}: cannot write into folder {}: {}", path, folder, std::strerror(errno)));
  if (!S_ISDIR(fs.st_mode)) throw IoError(fmt::format("{}: {} is not a folder", path, folder));
  if (::access(folder.c_str(), W_OK | X_OK) != 0)
    throw IoError(fmt::format("{}: cannot write into folder {}: {}", path, folder, std::strerror(errno)));
  return target;
}

OutputSet::OutputSet() {
  std::lock_guard lock(set_mutex);
  if (open_set) throw std::logic_error("OutputSet: a set is already open");
  open_set = this;
}

OutputSet::~OutputSet() {
  {
    std::lock_guard lock(set_mutex);
    if (open_set == this) open_set = nullptr;
  }
  if (committed_) return;
  for (const auto& s : staged_) {
    ::unlink(s.temporary.c_str());
    unregister_temporary(s.temporary);
  }
}

bool OutputSet::stage(const std::string& temporary, const std::string& target) {
  std::lock_guard lock(set_mutex);
  if (!open_set) return false;
  // A later output to the same target replaces the earlier one.
  for (auto& s : open_set->staged_)
    if (s.target == target) {
      ::unlink(s.temporary.c_str());
      unregister_temporary(s.temporary);
      s.temporary = temporary;
      return true;
    }
  open_set->staged_.push_back({temporary, target});
  return true;
}

bool OutputSet::stage_bytes(std::string&& bytes) {
  std::lock_guard lock(set_mutex);
  if (!open_set) return false;
  open_set->standard_output_ = std::move(bytes);
  open_set->has_standard_output_ = true;
  return true;
}

void OutputSet::commit() {
  {
    std::lock_guard lock(set_mutex);
    if (open_set == this) open_set = nullptr;
  }
  committed_ = true;
  std::size_t i = 0;
  try {
    for (; i < staged_.size(); ++i) rename_into_place(staged_[i].temporary, staged_[i].target, staged_[i].target);
    if (has_standard_output_) write_standard_output(standard_output_);
  } catch (...) {
    for (std::size_t j = i + 1; j < staged_.size(); ++j) {
      ::unlink(staged_[j].temporary.c_str());
      unregister_temporary(staged_[j].temporary);
    }
    throw;
  }
}

}  // namespace metrica::io
