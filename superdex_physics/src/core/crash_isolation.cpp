// Forked trial reads: see crash_isolation.h.

#include "core/crash_isolation.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <mutex>
#include <set>
#include <sstream>
#include <thread>
#include <utility>

#include "core/fnv_hash.h"
#include "superdex/physics/error.h"
#include "superdex/physics/real.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

// The contents of a file that passed: size (bytes) and 64-bit FNV-1a hash. Contents rather than
// path and time: a file rewritten within the clock's granularity keeps its modification time.
using FileIdentity = std::pair<std::uint64_t, std::uint64_t>;

// Size and hash of the file's bytes; false when it cannot be read.
bool identify(const std::string& path, FileIdentity& id) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  Fnv1a64 h;
  std::uint64_t n = 0;
  char buf[1 << 16];
  while (in) {
    in.read(buf, sizeof buf);
    const std::streamsize got = in.gcount();
    h.bytes(buf, static_cast<size_t>(got));
    n += static_cast<std::uint64_t>(got);
  }
  id = {n, h.value};
  return true;
}

std::mutex passed_mutex;
std::set<FileIdentity>& passed_files() {
  static std::set<FileIdentity> files;
  return files;
}

// In the child: crash signals end it at once where the runtime allows (a sanitizer may keep its
// own handler, which exits with an error status instead), without a core file, and silently:
// the parent reports the crash as an Error.
void die_plainly_on_faults() {
  for (const int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) signal(sig, SIG_DFL);
  const rlimit no_core{0, 0};
  setrlimit(RLIMIT_CORE, &no_core);
  const int null_fd = open("/dev/null", O_WRONLY);
  if (null_fd >= 0) {
    dup2(null_fd, STDOUT_FILENO);
    dup2(null_fd, STDERR_FILENO);
    close(null_fd);
  }
}

std::string seconds_text(double s) {
  std::ostringstream os;
  os << s;
  return os.str();
}

}  // namespace

void try_in_child_process(const std::string& path, const std::function<void()>& attempt,
                          const std::string& library, double timeout_seconds) {
  FileIdentity id;
  // an unreadable path is the reader's to report, with its own message
  if (!identify(path, id)) return;
  {
    std::lock_guard<std::mutex> g(passed_mutex);
    if (passed_files().count(id)) return;
  }

  const pid_t pid = fork();
  if (pid < 0) throw Error(path + ": cannot start a process to check the file (fork: " + std::strerror(errno) + ")");
  if (pid == 0) {
    die_plainly_on_faults();
    try {
      attempt();
    } catch (...) {
      // a file the reader rejects is fine here: the caller reads it again and gets the error
    }
    _exit(0);
  }

  // Wait for the child, polling so that a reader that hangs is stopped after the timeout.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_seconds);
  auto pause = std::chrono::microseconds(200);
  int status = 0;
  for (;;) {
    const pid_t r = waitpid(pid, &status, WNOHANG);
    if (r == pid) break;
    if (r < 0 && errno != EINTR) throw Error(path + ": lost the process checking the file (waitpid: " + std::strerror(errno) + ")");
    if (std::chrono::steady_clock::now() >= deadline) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      throw Error(path + ": " + library + " did not finish reading the file within " +
                  seconds_text(timeout_seconds) + " s (corrupt file?)");
    }
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, std::chrono::microseconds(20000));
  }
  if (WIFSIGNALED(status))
    throw Error(path + ": " + library + " crashed reading the file (signal " + std::to_string(WTERMSIG(status)) + ": " +
                strsignal(WTERMSIG(status)) + "): corrupt file?");
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw Error(path + ": " + library + " crashed reading the file (exit status " +
                std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + "): corrupt file?");
  std::lock_guard<std::mutex> g(passed_mutex);
  passed_files().insert(id);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
