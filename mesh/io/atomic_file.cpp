#include <metrica/error.hpp>
#include <metrica/io/atomic_file.hpp>

#include <fmt/core.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <unistd.h>

namespace metrica::io {

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
  static std::atomic<unsigned> counter{0};
  tmp_path_ = fmt::format("{}.tmp-{}-{}", path_, static_cast<long>(::getpid()), counter++);
  file_ = std::fopen(tmp_path_.c_str(), "wb");
  if (!file_) throw IoError(fmt::format("{}: cannot open for writing: {}", path_, std::strerror(errno)));
}

AtomicFile::~AtomicFile() {
  if (file_) {
    std::fclose(file_);
    std::remove(tmp_path_.c_str());
  }
}

void AtomicFile::write(const void* data, std::size_t size) {
  if (size == 0) return;
  if (std::fwrite(data, 1, size, file_) != size)
    throw IoError(fmt::format("{}: write failed: {}", path_, std::strerror(errno)));
}

void AtomicFile::commit() {
  std::FILE* f = file_;
  file_ = nullptr;
  const bool flushed = std::fflush(f) == 0;
  const int saved = errno;
  if (std::fclose(f) != 0 || !flushed) {
    std::remove(tmp_path_.c_str());
    throw IoError(fmt::format("{}: write failed: {}", path_, std::strerror(flushed ? errno : saved)));
  }
  if (std::rename(tmp_path_.c_str(), path_.c_str()) != 0) {
    const int err = errno;
    std::remove(tmp_path_.c_str());
    throw IoError(fmt::format("{}: cannot rename the finished output into place: {}", path_, std::strerror(err)));
  }
}

void write_file_atomically(const std::string& path, std::string_view bytes) {
  AtomicFile out(path);
  out.write(bytes);
  out.commit();
}

}  // namespace metrica::io
