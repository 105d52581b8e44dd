#pragma once
// A scene's HDF5 recording (Scene::start_recording; layout: docs/recording_format.md, "Scene
// recordings"). The step writes a frame after its post-step callbacks.

#include <memory>
#include <set>
#include <string>

#include "io/h5_file.h"
#include "superdex/physics/params/recording_params.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

class Scene;
struct SceneData;

class SceneRecording {
 public:
  // Creates (replaces) the file and writes the header and the actors present now; throws
  // superdex::Error naming the file when it cannot be written.
  SceneRecording(const Scene& scene, const std::string& path, const RecordingParams& params);
  // Closes the file (a failure to is logged).
  ~SceneRecording();
  SceneRecording(const SceneRecording&) = delete;
  SceneRecording& operator=(const SceneRecording&) = delete;

  // Writes a frame of the scene's state now, describing actors not seen before first. A failure
  // to write logs a warning (the first of a run only) and the recording goes on.
  void record_frame(const Scene& scene, double time_step);

  const std::string& path() const { return path_; }

 private:
  void write_frame(const Scene& scene, double time_step);
  void describe_new_actors(const Scene& scene);

  std::string path_;
  RecordingParams params_;
  h5::Writer file_;
  std::set<long long> described_;  // actor handles already under /actors
  long long frames_ = 0;
  bool warned_ = false;
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
