// Every output of a run as one transaction: files are written to
// temporaries beside their targets and renamed over them together, only
// when the whole run succeeded, so that a failed, killed or interrupted run
// never leaves a half-written file or a mix of old and new outputs. What
// goes to standard output ("-") is held in memory and written on commit,
// after the files.
//
// While an OutputSet is open, AtomicFile::commit() stages its finished
// temporary into the set instead of renaming it; OutputSet::commit() renames
// every staged file, and destroying an uncommitted set removes them.
// Temporaries are also removed when the process gets SIGINT or SIGTERM.
#pragma once

#include <string>
#include <vector>

namespace metrica::io {

// The file that writing `path` will replace, checked before any work: a
// symlink is followed (its target is replaced, the link kept); an existing
// target must be a regular file with a write permission bit (a read-only
// file, a folder, a FIFO or a device is refused); its folder must exist and
// be writable. Throws IoError naming the path and the reason. "-" (standard
// output) is returned as it is.
std::string writable_target(const std::string& path);

class OutputSet {
 public:
  OutputSet();   // becomes the open set (one at a time)
  ~OutputSet();  // removes what is staged unless committed
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  // Renames every staged temporary onto its target, in staging order, and
  // syncs their folders. The staged files were fsynced when written.
  void commit();
  std::size_t staged() const { return staged_.size(); }

  // Called by AtomicFile::commit(): false when no set is open.
  static bool stage(const std::string& temporary, const std::string& target);
  // The bytes for standard output (a later call replaces them); false when
  // no set is open.
  static bool stage_bytes(std::string&& bytes);

 private:
  struct Staged {
    std::string temporary, target;
  };
  std::vector<Staged> staged_;
  std::string standard_output_;
  bool has_standard_output_ = false;
  bool committed_ = false;
};

// Creates "FOLDER/.metrica-XXXXXX" exclusively (mkstemp) and registers it
// for the SIGINT/SIGTERM/SIGHUP handler, which unlinks every registered
// temporary and re-raises the signal. The signals are held from creation to
// registration, so no temporary escapes. Returns the open descriptor, or
// -1 with errno set.
int create_temporary(const std::string& folder, std::string& path);
void unregister_temporary(const std::string& path);

// The folder of a file path ("." for a bare name).
std::string folder_of(const std::string& path);

}  // namespace metrica::io
