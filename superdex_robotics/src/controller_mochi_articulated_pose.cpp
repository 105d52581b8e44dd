// MOCHI_ARTICULATED_POSE (controller_mochi_articulated_pose.h): the engine's pose controller on a
// bot's articulation, its params as JSON, and targets from link transforms or joint DOFs.

#include "superdex/robotics/controller_mochi_articulated_pose.h"

#include <fstream>

#include "superdex/physics/engine.h"

#include "builtin_support.h"
#include "builtins.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

using physics::PoseTrackingParams;
using physics::Transform;

// The JSON keys of PoseControllerParams' three arrays, and the arrays.
const char* const kArrays[] = {"jointTracking", "linkPosTracking", "linkRotTracking"};
std::vector<PoseTrackingParams>& array_of(physics::PoseControllerParams& p, int i) {
  std::vector<PoseTrackingParams>* arrays[] = {&p.joint_tracking, &p.link_pos_tracking, &p.link_rot_tracking};
  return *arrays[i];
}

PoseTrackingParams tracking_from_json(const nlohmann::json& j, const std::string& where) {
  if (!j.is_object()) throw Error(where + ": expected an object {\"stiffness\", \"damping\", \"saturation\"}");
  PoseTrackingParams t;
  for (const auto& [key, value] : j.items()) {
    if (!value.is_number()) throw Error(where + "." + key + ": expected a number");
    if (key == "stiffness") {
      t.stiffness = value.get<real>();
    } else if (key == "damping") {
      t.damping = value.get<real>();
    } else if (key == "saturation") {
      t.saturation = value.get<real>();
    } else {
      throw Error(where + "." + key + ": unknown key (stiffness, damping, saturation)");
    }
  }
  return t;
}

class MochiArticulatedPoseController final : public ControllerMochiArticulatedPose {
 public:
  explicit MochiArticulatedPoseController(const ComponentArgs& args)
      : scene_(args.scene), articulation_(articulation_of(args.scene, args.actor, kTypeName)) {
    const physics::ArticulatedShapeInfo info = scene_.articulated_shape_info(articulation_);
    parents_.assign(info.parents.begin(), info.parents.end());
    root_dofs_ = root_dofs(scene_, articulation_);
    // params given at creation (a bot file's entry, or create_controller's): set up at once
    if (!args.params.empty()) configure_from_scene_entry(args.params, "");
  }

  ~MochiArticulatedPoseController() override {
    // the physics controller goes with this one, unless its scene or actor went first
    if (!added_ || !physics::scene_exists(scene_.handle()) || !scene_.has_actor(articulation_)) return;
    if (scene_.has_pose_controller(articulation_)) scene_.remove_pose_controller(articulation_);
  }

  void reset() override { needs_reset_ = true; }

  void configure_from_scene_entry(const std::string& params, const std::string&) override {
    if (!params.empty()) set_params(ControllerMochiArticulatedPoseParams::from_json_text(params, kTypeName));
    initialize(true);
  }

  const ControllerMochiArticulatedPoseParams& params() const override { return params_; }

  void set_params(const ControllerMochiArticulatedPoseParams& params) override {
    if (added_) live("set_params").set_pose_controller_params(articulation_, params.pose_controller_params);
    params_ = params;
    has_params_ = true;
  }

  void initialize(bool remove_existing) override {
    Scene& scene = live("initialize");
    if (scene.has_pose_controller(articulation_)) {
      if (!remove_existing)
        throw Error(std::string(kTypeName) + ".initialize: the actor has a pose controller already; pass remove_existing=True to replace it");
      scene.remove_pose_controller(articulation_);
    }
    physics::PoseControllerParams p = params_.pose_controller_params;
    if (!has_params_) p.link_pos_tracking = p.link_rot_tracking = {PoseTrackingParams{}};
    scene.add_pose_controller(articulation_, p);
    added_ = true;
    needs_reset_ = false;
  }

  void compute_output(const ControllerMochiArticulatedPoseObsv&, const ControllerMochiArticulatedPoseTarget& target) override {
    const std::string what = std::string(kTypeName) + ".compute_output";
    if (!added_) throw Error(what + ": call initialize() first");
    Scene& scene = live("compute_output");
    const bool transforms = !target.local_to_parent_transforms.empty(), dofs = !target.pose_dofs.empty();
    if (transforms == dofs) throw Error(what + ": give exactly one of target.local_to_parent_transforms and target.pose_dofs");
    const int num_links = static_cast<int>(parents_.size());
    if (transforms) {
      if (static_cast<int>(target.local_to_parent_transforms.size()) != num_links)
        throw Error(what + ": target.local_to_parent_transforms must hold one transform per link (" + std::to_string(num_links) + "), got " +
                    std::to_string(target.local_to_parent_transforms.size()));
      // each link's world frame from its parent's (links come parents first)
      std::vector<Transform> X_WL(num_links);
      for (int i = 0; i < num_links; ++i)
        X_WL[i] = (parents_[i] < 0 ? target.world_from_root : X_WL[parents_[i]]) * target.local_to_parent_transforms[i];
      if (needs_reset_) {
        scene.reset_target_link_transforms(articulation_, X_WL);
      } else {
        scene.set_target_link_transforms(articulation_, X_WL);
      }
    } else {
      const int n = scene.num_dofs(articulation_);
      if (static_cast<int>(target.pose_dofs.size()) != n - root_dofs_)
        throw Error(what + ": target.pose_dofs must hold the " + std::to_string(n - root_dofs_) + " DOFs below the root, got " +
                    std::to_string(target.pose_dofs.size()));
      // a free root's DOFs: world_from_root's translation and rotation vector
      VecX pose(n);
      if (root_dofs_ == 6) {
        pose.head<3>() = target.world_from_root.translation;
        const Eigen::AngleAxis<real> aa(target.world_from_root.rotation.normalized());
        pose.segment<3>(3) = aa.angle() * aa.axis();
      }
      for (int i = 0; i < n - root_dofs_; ++i) pose[root_dofs_ + i] = target.pose_dofs[i];
      if (needs_reset_) {
        scene.reset_target_pose(articulation_, pose);
      } else {
        scene.set_target_pose(articulation_, pose);
      }
    }
    needs_reset_ = false;
  }

 private:
  Scene& live(const char* what) {
    if (!physics::scene_exists(scene_.handle()) || !scene_.has_actor(articulation_))
      throw Error(std::string(kTypeName) + "." + what + ": its articulation (or its scene) was destroyed");
    return scene_;
  }

  Scene scene_;
  ActorHandle articulation_;
  std::vector<int> parents_;
  int root_dofs_ = 0;
  ControllerMochiArticulatedPoseParams params_;
  bool has_params_ = false, added_ = false, needs_reset_ = false;
};

}  // namespace

ControllerMochiArticulatedPoseParams ControllerMochiArticulatedPoseParams::from_json_text(const std::string& text, const std::string& where) {
  ComponentParams p(text, where);
  p.allow_only({"poseControllerParams"});
  ControllerMochiArticulatedPoseParams out;
  if (!p.has("poseControllerParams")) return out;
  const nlohmann::json& j = p.json().at("poseControllerParams");
  const std::string base = p.at("poseControllerParams");
  if (!j.is_object()) throw Error(base + ": expected an object");
  for (const auto& [key, value] : j.items()) {
    int k = 0;
    while (k < 3 && key != kArrays[k]) ++k;
    if (k == 3) throw Error(base + "." + key + ": unknown key (jointTracking, linkPosTracking, linkRotTracking)");
    if (!value.is_array()) throw Error(base + "." + key + ": expected a list of {stiffness, damping, saturation}");
    for (size_t i = 0; i < value.size(); ++i)
      array_of(out.pose_controller_params, k).push_back(tracking_from_json(value[i], base + "." + key + "[" + std::to_string(i) + "]"));
  }
  return out;
}

std::string ControllerMochiArticulatedPoseParams::to_json_text() const {
  nlohmann::json arrays = nlohmann::json::object();
  physics::PoseControllerParams copy = pose_controller_params;
  for (int k = 0; k < 3; ++k) {
    nlohmann::json list = nlohmann::json::array();
    for (const PoseTrackingParams& t : array_of(copy, k))
      list.push_back({{"stiffness", t.stiffness}, {"damping", t.damping}, {"saturation", t.saturation}});
    arrays[kArrays[k]] = list;
  }
  return nlohmann::json{{"poseControllerParams", arrays}}.dump(2);
}

ControllerMochiArticulatedPoseParams ControllerMochiArticulatedPoseParams::load_from_file(const std::string& path) {
  const auto first = path.find_first_not_of(" \t\r\n");
  if (first == std::string::npos || path[first] == '{')
    throw Error("ControllerMochiArticulatedPoseParams.load_from_file: path: expected a file path, got '" + path + "'");
  return from_json_text(path, "ControllerMochiArticulatedPoseParams.load_from_file('" + path + "')");
}

void ControllerMochiArticulatedPoseParams::save_to_file(const std::string& path) const {
  std::ofstream out(path);
  if (!out) throw Error("ControllerMochiArticulatedPoseParams.save_to_file: path: cannot write '" + path + "'");
  out << to_json_text() << "\n";
}

std::unique_ptr<Component> make_mochi_articulated_pose_controller(const ComponentArgs& args) {
  return std::make_unique<MochiArticulatedPoseController>(args);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics
