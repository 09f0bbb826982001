#include <metrica/error.hpp>
#include <metrica/io/atomic_file.hpp>
#include <metrica/io/output_set.hpp>

#include <fmt/core.h>

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace metrica::io {

namespace {

mode_t new_file_mode() {
  static const mode_t mode = [] {
    const mode_t mask = ::umask(0);
    ::umask(mask);
    return static_cast<mode_t>(0666 & ~mask);
  }();
  return mode;
}

void sync_folder(const std::string& folder) {
  const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd < 0) return;
  ::fsync(fd);  // best effort: some file systems refuse fsync on folders
  ::close(fd);
}

// The descriptor of the standard output for "-" (1 until diverted).
int standard_output_fd = STDOUT_FILENO;

}  // namespace

void divert_standard_output() {
  if (standard_output_fd != STDOUT_FILENO) return;
  std::fflush(stdout);
  const int kept = ::dup(STDOUT_FILENO);
  if (kept < 0) throw IoError(fmt::format("standard output: cannot keep it: {}", std::strerror(errno)));
  if (::dup2(STDERR_FILENO, STDOUT_FILENO) < 0) {
    const int err = errno;
    ::close(kept);
    throw IoError(fmt::format("standard output: cannot send progress to standard error: {}", std::strerror(err)));
  }
  standard_output_fd = kept;
}

void write_standard_output(std::string_view bytes) {
  std::fflush(stdout);
  while (!bytes.empty()) {
    const ssize_t n = ::write(standard_output_fd, bytes.data(), bytes.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw IoError(fmt::format("standard output: write failed: {}", std::strerror(errno)));
    bytes.remove_prefix(static_cast<std::size_t>(n));
  }
}

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)), target_(writable_target(path_)) {
  if (is_standard_output(path_)) {
    to_standard_output_ = true;
    return;
  }
  const int fd = create_temporary(folder_of(target_), tmp_path_);
  if (fd < 0)
    throw IoError(fmt::format("{}: cannot create a temporary file beside it: {}", path_, std::strerror(errno)));
  struct stat st {};
  const mode_t mode = ::stat(target_.c_str(), &st) == 0 ? (st.st_mode & 07777) : new_file_mode();
  ::fchmod(fd, mode);
  file_ = ::fdopen(fd, "wb");
  if (!file_) {
    const int err = errno;
    ::close(fd);
    ::unlink(tmp_path_.c_str());
    unregister_temporary(tmp_path_);
    throw IoError(fmt::format("{}: cannot open for writing: {}", path_, std::strerror(err)));
  }
}

AtomicFile::~AtomicFile() {
  if (file_) {
    std::fclose(file_);
    ::unlink(tmp_path_.c_str());
    unregister_temporary(tmp_path_);
  }
}

void AtomicFile::write(const void* data, std::size_t size) {
  if (size == 0) return;
  if (to_standard_output_) {
    bytes_.append(static_cast<const char*>(data), size);
    return;
  }
  if (std::fwrite(data, 1, size, file_) != size)
    throw IoError(fmt::format("{}: write failed: {}", path_, std::strerror(errno)));
}

void AtomicFile::write_at(std::uint64_t offset, const void* data, std::size_t size) {
  if (to_standard_output_) {
    if (offset + size > bytes_.size()) throw IoError(fmt::format("{}: write past the end", path_));
    bytes_.replace(static_cast<std::size_t>(offset), size, static_cast<const char*>(data), size);
    return;
  }
  const bool ok = std::fflush(file_) == 0 && ::fseeko(file_, static_cast<off_t>(offset), SEEK_SET) == 0 &&
                  std::fwrite(data, 1, size, file_) == size && ::fseeko(file_, 0, SEEK_END) == 0;
  if (!ok) throw IoError(fmt::format("{}: write failed: {}", path_, std::strerror(errno)));
}

void AtomicFile::commit() {
  if (to_standard_output_) {
    to_standard_output_ = false;
    if (OutputSet::stage_bytes(std::move(bytes_))) return;
    write_standard_output(bytes_);
    return;
  }
  std::FILE* f = file_;
  file_ = nullptr;
  int err = 0;
  if (std::fflush(f) != 0 || ::fsync(::fileno(f)) != 0) err = errno;
  if (std::fclose(f) != 0 && err == 0) err = errno;
  if (err != 0) {
    ::unlink(tmp_path_.c_str());
    unregister_temporary(tmp_path_);
    throw IoError(fmt::format("{}: write failed: {}", path_, std::strerror(err)));
  }
  if (OutputSet::stage(tmp_path_, target_)) return;
  rename_into_place(tmp_path_, target_, path_);
}

void rename_into_place(const std::string& temporary, const std::string& target, const std::string& shown) {
  if (std::rename(temporary.c_str(), target.c_str()) != 0) {
    const int err = errno;
    ::unlink(temporary.c_str());
    unregister_temporary(temporary);
    throw IoError(fmt::format("{}: cannot rename the finished output into place: {}", shown, std::strerror(err)));
  }
  unregister_temporary(temporary);
  sync_folder(folder_of(target));
}

void write_file_atomically(const std::string& path, std::string_view bytes) {
  AtomicFile out(path);
  out.write(bytes);
  out.commit();
}

}  // namespace metrica::io
