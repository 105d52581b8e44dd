/// @file recording_reader_test.cpp
/// The replay reader's checks (server/recording_reader.h): a valid recording is read whole and
/// its frames counted; each kind of defect is refused naming the file's line and field.

#include <gmock/gmock.h>

#include <filesystem>
#include <fstream>

#include "recording_reader.h"
#include "superdex/physics/error.h"

namespace superdex::physics::debug {
namespace {

using ::testing::HasSubstr;

std::string write(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / ("superdex_" + name + ".jsonl");
  std::ofstream(path) << text;
  return path.string();
}

std::string error_of(const std::string& text) {
  try {
    read_recording(write("bad", text));
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

const std::string kHeader = R"({"type":"header","format":"superdex-recording","version":1,"units":"SI","frameInterval":0})" "\n";
const std::string kScene = R"({"type":"scene","scene":3,"name":"s","gravity":[0,0,-9.81]})" "\n";

TEST(RecordingReaderTest, ReadsAValidRecordingAndCountsFrames) {
  const std::string frame = R"({"type":"frame","scene":3,"step":1,"t":0.01,"links":{"4":[0,0,1,0,0,0,1]},"contacts":[],"joints":{},"signals":{}})" "\n";
  const RecordingLines r = read_recording(write("good", kHeader + kScene + "\n" + frame + frame + R"({"type":"future","x":1})" "\n"));
  EXPECT_EQ(r.lines.size(), 5u);  // the blank line is dropped, the unknown type kept
  EXPECT_EQ(r.frames, 2u);
}

TEST(RecordingReaderTest, DefectsNameTheLineAndField) {
  EXPECT_THAT(error_of(""), HasSubstr("is empty"));
  EXPECT_THAT(error_of("hello\n"), HasSubstr("line 1: not a SuperDex recording"));
  EXPECT_THAT(error_of(R"({"type":"header","format":"superdex-recording","version":2})" "\n"),
              HasSubstr("line 1: header.version: recording format version 2 is not supported"));
  EXPECT_THAT(error_of(kHeader + kScene + "{oops\n"), HasSubstr("line 3: not valid JSON"));
  EXPECT_THAT(error_of(kHeader + kScene + R"({"type":"frame","scene":3,"t":"x"})" "\n"), HasSubstr("line 3: frame.t: expected a number"));
  EXPECT_THAT(error_of(kHeader + R"({"type":"frame","scene":3,"t":0})" "\n"),
              HasSubstr("line 2: frame.scene: scene 3 was not described by an earlier scene line"));
  EXPECT_THAT(error_of(kHeader + kScene + R"({"type":"frame","scene":3,"t":0,"links":{"1":[0,0]}})" "\n"),
              HasSubstr("line 3: frame.links.1: expected 7 numbers"));
}

}  // namespace
}  // namespace superdex::physics::debug
