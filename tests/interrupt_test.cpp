// Nothing lost on interruption: a process killed while writing leaves the
// previous result intact and no temporary files (sim/util/atomic_file.h), and a
// long `gyrotherm score` run killed with SIGINT leaves its previous outputs.

#include <gtest/gtest.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <map>
#include <thread>

#include "cli_runner.h"
#include "sim/util/atomic_file.h"

namespace gyrotherm {
namespace {

using namespace gyrotherm::testing;

std::vector<std::string> names_in(const std::filesystem::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : std::filesystem::directory_iterator(dir)) out.push_back(e.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

TEST(Interrupt, SignalWhileWritingKeepsThePreviousFileAndRemovesTheTemporary) {
  ScratchDir dir;
  const auto target = dir / "result.json";
  write_file_atomically(target, "previous result\n");
  for (int signal_number : {SIGINT, SIGTERM}) {
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      install_interrupt_cleanup();
      AtomicFile file(target);
      file.stream() << "half of a new res" << std::flush;
      ::raise(signal_number);
      ::_exit(0);  // not reached: the signal ends the process
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFSIGNALED(status)) << "the signal still ends the process";
    EXPECT_EQ(WTERMSIG(status), signal_number);
    EXPECT_EQ(slurp(target), "previous result\n");
    EXPECT_EQ(names_in(dir.path()), std::vector<std::string>{"result.json"});
  }
}

TEST(Interrupt, KillingALongScoreRunLeavesThePreviousScoreboard) {
  ScratchDir dir;
  write_text(dir / "short.toml",
             "name = \"short\"\nseed = 3\nstart_c = 20.0\nrig = \"" +
                 source_path("scenarios/rig_shield.toml") + "\"\ngyro = \"" +
                 source_path("scenarios/gyro.toml") +
                 "\"\n[[segment]]\nkind = \"hold\"\ntemp_c = 20.0\nduration_min = 30\n"
                 "[[segment]]\nkind = \"ramp\"\ntarget_c = 60.0\nrate_c_per_min = 5.0\n"
                 "[[segment]]\nkind = \"hold\"\ntemp_c = 60.0\nduration_min = 60\n");
  const auto first = testing::run_cli(dir, "score short.toml --engines ols,iafsa --trials 3 --out out");
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const auto before = names_in(dir / "out");
  std::map<std::string, std::string> contents;
  for (const auto& n : before) contents[n] = slurp(dir / "out" / n);

  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    if (::chdir(dir.path().c_str()) != 0) ::_exit(99);
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1);
    ::dup2(null, 2);
    ::execl(GYROTHERM_CLI, GYROTHERM_CLI, "score", "short.toml", "--trials", "100000", "--out", "out",
            static_cast<char*>(nullptr));
    ::_exit(98);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  ASSERT_EQ(::kill(child, SIGINT), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT) << "status " << status;
  EXPECT_EQ(names_in(dir / "out"), before) << "no temporary or partial file";
  for (const auto& [n, text] : contents) EXPECT_EQ(slurp(dir / "out" / n), text) << n;
}

}  // namespace
}  // namespace gyrotherm
