// CONTACT_FORCE: the total contact force applied TO a link by everything touching it.
//
// Signal: [fx, fy, fz] (N), in the world frame (pressing down on a surface reads +z) or, with
// "frame": "link", in the sensor frame (the link frame turned by parentFromSensor). It registers
// the link's TOTAL_CONTACT_FORCE query itself (cancelled when the sensor is destroyed) and reads
// it after each step.
//
// Params
//   "frame"  "world" | "link"   default "world"

#include "builtin_support.h"
#include "builtins.h"
#include "superdex/physics/engine.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

class ContactForceSensor final : public SensorComponent {
 public:
  explicit ContactForceSensor(const ComponentArgs& args) : scene_(args.scene), link_(args.actor), R_LS_(args.parent_from_sensor.rotation) {
    require_link(scene_, link_, "CONTACT_FORCE");
    configure(args.params);
    query_ = scene_.register_query(link_, physics::QueryType::TotalContactForce);
  }

  ~ContactForceSensor() override {
    if (physics::scene_exists(scene_.handle()) && scene_.has_actor(link_)) scene_.cancel_query(link_, query_);
  }

  void reset() override { signal_.setZero(); }

  void configure(const std::string& json) override {
    ComponentParams p(json, "CONTACT_FORCE");
    p.allow_only({"frame"});
    const std::string frame = p.text("frame", in_link_frame_ ? "link" : "world");
    if (frame != "world" && frame != "link") throw Error(p.at("frame") + ": expected \"world\" or \"link\", got \"" + frame + "\"");
    p.apply_rate(*this);
    in_link_frame_ = frame == "link";
  }

  void update(const Tick&) override {
    const Vec3 f_W = scene_.contact_force(link_);
    // "link": the sensor frame's axes (the link frame turned by parentFromSensor)
    signal_ = in_link_frame_ ? Vec3((scene_.root_transform(link_).rotation * R_LS_).conjugate() * f_W) : f_W;
  }

  VecX signal() const override { return signal_; }

 private:
  Scene scene_;
  ActorHandle link_;
  std::int64_t query_ = 0;
  bool in_link_frame_ = false;
  Vec3 signal_ = Vec3::Zero();
  Quat R_LS_;  // sensor frame orientation in the link frame
};

}  // namespace

std::unique_ptr<Component> make_contact_force_sensor(const ComponentArgs& args) { return std::make_unique<ContactForceSensor>(args); }

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics
