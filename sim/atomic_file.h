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

namespace gyrotherm::sim {

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
  std::filesystem::path temporary_;
  std::ofstream out_;
  bool committed_ = false;
};

// Writes a whole string atomically.
void write_file_atomically(const std::filesystem::path& target, std::string_view contents);

}  // namespace gyrotherm::sim
