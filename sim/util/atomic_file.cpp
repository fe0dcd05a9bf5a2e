#include "sim/util/atomic_file.h"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cstring>
#include <system_error>

#include "sim/util/input_error.h"

namespace gyrotherm {
namespace {

// Temporaries in flight, readable from a signal handler (no allocation, no
// locks): a slot is claimed with an atomic flag, its path copied in before the
// flag is published.
constexpr int kSlots = 64;
constexpr std::size_t kPathBytes = 4096;
struct Slot {
  std::atomic<int> state{0};  // 0 free, 1 being filled, 2 live
  char path[kPathBytes];
};
Slot slots[kSlots];

int claim_slot(const std::filesystem::path& p) {
  const std::string text = p.string();
  if (text.size() + 1 > kPathBytes) return -1;
  for (int i = 0; i < kSlots; ++i) {
    int expected = 0;
    if (!slots[i].state.compare_exchange_strong(expected, 1)) continue;
    std::memcpy(slots[i].path, text.c_str(), text.size() + 1);
    slots[i].state.store(2);
    return i;
  }
  return -1;
}

void release_slot(int i) {
  if (i >= 0) slots[i].state.store(0);
}

extern "C" void remove_temporaries_and_reraise(int signal_number) {
  for (Slot& slot : slots)
    if (slot.state.load() == 2) ::unlink(slot.path);
  ::signal(signal_number, SIG_DFL);
  ::raise(signal_number);
}

}  // namespace

void install_interrupt_cleanup() {
  struct sigaction action {};
  action.sa_handler = &remove_temporaries_and_reraise;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND;
  for (int signal_number : {SIGINT, SIGTERM, SIGHUP}) ::sigaction(signal_number, &action, nullptr);
}

TemporaryPath::TemporaryPath(std::filesystem::path path)
    : path_(std::move(path)), slot_(claim_slot(path_)) {}

TemporaryPath::~TemporaryPath() {
  if (!released_) {
    std::error_code ignored;
    std::filesystem::remove(path_, ignored);
  }
  release_slot(slot_);
}

void TemporaryPath::release() {
  released_ = true;
  release_slot(slot_);
  slot_ = -1;
}

namespace {
// Same directory as the target so that the rename stays within one file
// system; the process id keeps concurrent writers apart.
std::filesystem::path temporary_for(const std::filesystem::path& target) {
  std::filesystem::path t = target;
  t += ".tmp." + std::to_string(::getpid());
  return t;
}
}  // namespace

namespace {

// An output is a regular file: renaming over a device (`-o /dev/null`, as
// root) would replace the device with the output, and a folder cannot be
// replaced at all.
std::filesystem::path regular_target(std::filesystem::path target) {
  std::error_code ec;
  const auto status = std::filesystem::status(target, ec);
  if (!ec && std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
    throw InputError(target.string() + ": not a regular file (a device or a folder); give the path of a file to write");
  return target;
}

}  // namespace

AtomicFile::AtomicFile(std::filesystem::path target)
    : target_(regular_target(std::move(target))), temporary_(temporary_for(target_)) {
  out_.open(temporary_.path(), std::ios::binary | std::ios::trunc);
  if (!out_)
    throw InputError(target_.string() + ": cannot create the output file (is the folder there "
                     "and writable?)");
}

AtomicFile::~AtomicFile() { out_.close(); }

void AtomicFile::commit() {
  out_.flush();
  const bool ok = static_cast<bool>(out_);
  out_.close();
  if (!ok || out_.fail())
    throw InputError(target_.string() + ": writing the output failed (disk full?)");
  std::error_code error;
  std::filesystem::rename(temporary_.path(), target_, error);
  if (error) throw InputError(target_.string() + ": cannot rename into place: " + error.message());
  temporary_.release();
}

void write_file_atomically(const std::filesystem::path& target, std::string_view contents) {
  AtomicFile file(target);
  file.stream() << contents;
  file.commit();
}

}  // namespace gyrotherm
