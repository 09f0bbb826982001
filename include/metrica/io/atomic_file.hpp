// Output written to a temporary file beside the target and renamed over it
// on commit(), so that a failed or interrupted run never leaves a
// half-written mesh where a user expects a good one.
#pragma once

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
  // Flushes, closes and renames the temporary file onto the target.
  void commit();

 private:
  std::string path_;
  std::string tmp_path_;
  std::FILE* file_ = nullptr;
};

// Writes `bytes` to `path` atomically.
void write_file_atomically(const std::string& path, std::string_view bytes);

}  // namespace metrica::io
