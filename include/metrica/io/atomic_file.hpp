// Output written to a temporary file beside the target and renamed over it
// on commit(), so that a failed or interrupted run never leaves a
// half-written mesh where a user expects a good one. The temporary has a
// short name of its own (".metrica-XXXXXX", created exclusively), takes the
// replaced file's permissions (else 0666 less the umask) and is fsynced
// before the rename. Within an open OutputSet the rename waits for the
// set's commit (output_set.hpp).
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

namespace metrica::io {

class AtomicFile {
 public:
  explicit AtomicFile(std::string path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  void write(const void* data, std::size_t size);
  void write(std::string_view text) { write(text.data(), text.size()); }
  // Overwrites bytes already written (a binary keyword's next offset),
  // then goes on at the end.
  void write_at(std::uint64_t offset, const void* data, std::size_t size);
  // Flushes, syncs, closes and renames the temporary file onto the target
  // (or stages it in the open OutputSet).
  void commit();

 private:
  std::string path_;    // as the user named it
  std::string target_;  // the file replaced (symlinks followed)
  std::string tmp_path_;
  std::FILE* file_ = nullptr;
};

// Writes `bytes` to `path` atomically.
void write_file_atomically(const std::string& path, std::string_view bytes);

// Renames `temporary` onto `target` and syncs the target's folder.
void rename_into_place(const std::string& temporary, const std::string& target, const std::string& shown);

}  // namespace metrica::io
