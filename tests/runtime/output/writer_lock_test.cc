// The writer lock (runtime/output/writer_lock.h) seen from another process: a forked child
// holds it on a file, as a running ffrsim holds its result file.
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <string>

#include <catch2/catch.hpp>

#include "common/base/error.h"
#include "runtime/output/restart_record.h"
#include "runtime/output/writer_lock.h"

using namespace ffriga;

namespace {

// A child process that takes the writer lock on `path` and waits to be killed; its pid once
// it holds the lock.
pid_t lockingChild(const std::string& path) {
  int ready[2];
  REQUIRE(::pipe(ready) == 0);
  const pid_t pid = ::fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    ::close(ready[0]);
    try {
      WriterLock lock(path);
      const char ok = 1;
      if (::write(ready[1], &ok, 1) != 1) ::_exit(1);
      for (;;) ::pause();
    } catch (...) {
      ::_exit(1);
    }
  }
  ::close(ready[1]);
  char ok = 0;
  REQUIRE(::read(ready[0], &ok, 1) == 1);
  ::close(ready[0]);
  return pid;
}

}  // namespace

TEST_CASE("writer lock: another process's lock is named before the file is read", "[output]") {
  // ffrsim --restart on a result file that another ffrsim still writes must say so, whatever
  // the file holds at that moment (here: no HDF5 file at all, as before the writer's first
  // flush; the restart record's own complaints would be the wrong reason).
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("ffriga_lock_" + std::to_string(::getpid()) + ".h5"))
                               .string();
  std::filesystem::remove(path);
  const pid_t child = lockingChild(path);
  CHECK(WriterLock::holder(path) == static_cast<long>(child));
  const std::string who = "(process " + std::to_string(child) + ")";
  CHECK_THROWS_WITH(WriterLock::refuseIfHeld(path),
                    Catch::Contains("being written by another ffrsim") && Catch::Contains(who));
  CHECK_THROWS_WITH(readRestartRecord(path), Catch::Contains("being written by another ffrsim"));
  CHECK_THROWS_AS(WriterLock(path), InputError);
  ::kill(child, SIGKILL);
  int status = 0;
  REQUIRE(::waitpid(child, &status, 0) == child);
  // Gone with the process, however it ended: the file is free again.
  CHECK(WriterLock::holder(path) == 0);
  CHECK_NOTHROW(WriterLock::refuseIfHeld(path));
  CHECK_THROWS_WITH(readRestartRecord(path), !Catch::Contains("being written"));
  std::filesystem::remove(path);
}
