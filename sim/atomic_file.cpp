#include "sim/atomic_file.h"

#include <unistd.h>

#include <system_error>

#include "sim/input_error.h"

namespace gyrotherm::sim {

AtomicFile::AtomicFile(std::filesystem::path target) : target_(std::move(target)) {
  // Same directory as the target so that the rename stays within one file
  // system; the process id keeps concurrent writers apart.
  temporary_ = target_;
  temporary_ += ".tmp." + std::to_string(::getpid());
  out_.open(temporary_, std::ios::binary | std::ios::trunc);
  if (!out_)
    throw InputError(target_.string() + ": cannot create the output file (is the folder there "
                     "and writable?)");
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    out_.close();
    std::error_code ignored;
    std::filesystem::remove(temporary_, ignored);
  }
}

void AtomicFile::commit() {
  out_.flush();
  const bool ok = static_cast<bool>(out_);
  out_.close();
  if (!ok || out_.fail())
    throw InputError(target_.string() + ": writing the output failed (disk full?)");
  std::error_code error;
  std::filesystem::rename(temporary_, target_, error);
  if (error) throw InputError(target_.string() + ": cannot rename into place: " + error.message());
  committed_ = true;
}

void write_file_atomically(const std::filesystem::path& target, std::string_view contents) {
  AtomicFile file(target);
  file.stream() << contents;
  file.commit();
}

}  // namespace gyrotherm::sim
