// try_in_child_process: a crash or a hang of the trial becomes an Error naming the file; a trial
// that finishes (or throws) lets the caller go on, and the same contents are not tried twice.

#include "core/crash_isolation.h"

#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <thread>

#include "superdex/physics/error.h"

namespace sdp = superdex::physics;

namespace {

// A scratch file with the given contents; removed at the end of the test.
struct ScratchFile {
  std::filesystem::path path;
  explicit ScratchFile(const std::string& name, const std::string& contents)
      : path(std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid()))) {
    std::ofstream(path, std::ios::binary) << contents;
  }
  ~ScratchFile() { std::filesystem::remove(path); }
};

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const superdex::Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(CrashIsolation, ACrashInTheChildIsAnErrorNamingTheFileAndTheLibrary) {
  const ScratchFile f("crash_isolation_segv", "segv");
  const std::string m = message_of([&] {
    sdp::try_in_child_process(f.path.string(), [] { std::raise(SIGSEGV); }, "the test library");
  });
  EXPECT_NE(m.find(f.path.string() + ": the test library crashed reading the file ("), std::string::npos) << m;
  EXPECT_NE(m.find("corrupt file?"), std::string::npos) << m;
}

TEST(CrashIsolation, AChildThatHangsIsStoppedAfterTheTimeout) {
  const ScratchFile f("crash_isolation_hang", "hang");
  const auto start = std::chrono::steady_clock::now();
  const std::string m = message_of([&] {
    sdp::try_in_child_process(f.path.string(), [] { std::this_thread::sleep_for(std::chrono::seconds(60)); },
                              "the test library", 0.5);
  });
  EXPECT_NE(m.find("the test library did not finish reading the file within 0.5 s"), std::string::npos) << m;
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(30));
}

TEST(CrashIsolation, AFinishedOrRejectingTrialPassesAndIsNotRepeated) {
  const ScratchFile f("crash_isolation_ok", "fine contents");
  // the child's work is invisible to the parent: count trials through a file the child writes
  const ScratchFile marker("crash_isolation_marker", "");
  const auto attempt = [&] {
    std::ofstream(marker.path, std::ios::app) << "x";
    throw superdex::Error("rejected: the caller reads it again and reports this");
  };
  EXPECT_NO_THROW(sdp::try_in_child_process(f.path.string(), attempt, "the test library"));
  EXPECT_NO_THROW(sdp::try_in_child_process(f.path.string(), attempt, "the test library"));
  EXPECT_EQ(std::filesystem::file_size(marker.path), 1u);
  // new contents are tried again, even at the same path
  std::ofstream(f.path, std::ios::binary) << "other contents";
  EXPECT_NO_THROW(sdp::try_in_child_process(f.path.string(), attempt, "the test library"));
  EXPECT_EQ(std::filesystem::file_size(marker.path), 2u);
}

TEST(CrashIsolation, AMissingFileIsLeftToTheReader) {
  EXPECT_NO_THROW(sdp::try_in_child_process("/nonexistent/superdex/file.mochi.h5", [] { std::abort(); }, "x"));
}
