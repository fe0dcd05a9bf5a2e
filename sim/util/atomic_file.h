#pragma once
// Output files are never half-written: AtomicFile writes to a temporary file
// beside the target and renames it over the target on commit() (rename(2) is
// atomic within a file system). If commit() is never reached (an error, an
// exception), the destructor removes the temporary file and the previous
// target, if any, is left intact.
//
//   AtomicFile out("run.csv");
//   out.stream() << ...;
//   out.commit();

#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

namespace gyrotherm {

// A temporary file that an interrupting signal removes (see
// install_interrupt_cleanup); removed on destruction unless released.
class TemporaryPath {
 public:
  explicit TemporaryPath(std::filesystem::path path);
  ~TemporaryPath();
  TemporaryPath(const TemporaryPath&) = delete;
  TemporaryPath& operator=(const TemporaryPath&) = delete;
  const std::filesystem::path& path() const { return path_; }
  // The file has been renamed into place (or is wanted): keep it.
  void release();

 private:
  std::filesystem::path path_;
  int slot_ = -1;  // in the interrupt-cleanup table, -1 if it was full
  bool released_ = false;
};

class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path target);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ostream& stream() { return out_; }
  // Flush, check for write errors, and rename over the target. Throws
  // InputError naming the file if anything failed.
  void commit();

  const std::filesystem::path& target() const { return target_; }

 private:
  std::filesystem::path target_;
  TemporaryPath temporary_;
  std::ofstream out_;
};

// Installs SIGINT/SIGTERM/SIGHUP handlers that remove every AtomicFile
// temporary still open, then let the signal end the process as it would have
// (so an interrupted run leaves the previous results and no litter). The
// temporaries are kept in a fixed table of slots that the handler can read
// without allocating: the one piece of process-wide state, because a signal
// handler can reach nothing else. Call once from main().
void install_interrupt_cleanup();

// Writes a whole string atomically.
void write_file_atomically(const std::filesystem::path& target, std::string_view contents);

}  // namespace gyrotherm
