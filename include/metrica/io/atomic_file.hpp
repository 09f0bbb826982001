// Output written to a temporary file beside the target and renamed over it
// on commit(), so that a failed or interrupted run never leaves a
// half-written mesh where a user expects a good one. The temporary has a
// short name of its own (".metrica-XXXXXX", created exclusively), takes the
// replaced file's permissions (else 0666 less the umask) and is fsynced
// before the rename. Within an open OutputSet the rename waits for the
// set's commit (output_set.hpp).
//
// The path "-" (or /dev/stdout) is the standard output: the bytes are kept in memory and
// written out on commit (or on the set's commit), so that standard output
// too gets all of a successful run or nothing.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

namespace metrica::io {

// "-" (or /dev/stdout, whose target a temporary cannot be renamed onto):
// standard output.
inline bool is_standard_output(std::string_view path) { return path == "-" || path == "/dev/stdout"; }

// Keeps the process's standard output for the outputs named "-" and sends
// what the program prints from now on to standard error (a command that
// writes its result to standard output keeps it free of progress lines).
void divert_standard_output();

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
  std::string bytes_;  // standard output: everything written, until commit
  bool to_standard_output_ = false;
};

// Writes `bytes` to the standard output kept by divert_standard_output()
// (else the process's). Throws IoError when the write fails.
void write_standard_output(std::string_view bytes);

// Writes `bytes` to `path` atomically.
void write_file_atomically(const std::string& path, std::string_view bytes);

// Renames `temporary` onto `target` and syncs the target's folder.
void rename_into_place(const std::string& temporary, const std::string& target, const std::string& shown);

}  // namespace metrica::io
