// TACTILE_PAD: a grid of taxels on a rectangular pad fixed to a link, each reading the contact
// force pressed into the pad over its cell (the fingertip pads of hands such as the Revo2).
//
// Pad frame: the sensor frame (parentFromSensor, in the link frame) moved by "pad_from_sensor".
// The pad spans [-size[0]/2, size[0]/2] along its x axis in `cols` columns and
// [-size[1]/2, size[1]/2] along its y axis in `rows` rows; its outward normal is +z.
// Signal: rows x cols values (N), row-major (row r, column c at r * cols + c, row 0 at -y, column
// 0 at -x): for each contact of the link in the last step whose point lies over the cell and
// within "thickness" of the pad plane, the force component pushing into the pad, -f . z (only
// pressing counts, never pulling). The sum over the grid is the pad's normal load.
//
// Params
//   "rows", "cols"       taxels along y and x, 1 to 1024 each      default 8 x 8
//   "size"               [width along x, height along y] (m)      default [0.01, 0.01]
//   "pad_from_sensor"    {rotation [x, y, z, w], translation [x, y, z] m}   default identity
//   "thickness"          half-width of the band about the pad plane in which contacts count (m),
//                        default 0.005

#include <cmath>

#include "builtin_support.h"
#include "builtins.h"
#include "superdex/physics/engine.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

constexpr const char* kType = "TACTILE_PAD";

class TactilePadSensor final : public SensorComponent {
 public:
  explicit TactilePadSensor(const ComponentArgs& args) : scene_(args.scene), link_(args.actor), X_LS_(args.parent_from_sensor) {
    require_link(scene_, link_, kType);
    configure(args.params);
    query_ = scene_.register_query(link_, physics::QueryType::ContactPoints);
  }

  ~TactilePadSensor() override {
    if (physics::scene_exists(scene_.handle()) && scene_.has_actor(link_)) scene_.cancel_query(link_, query_);
  }

  void reset() override { taxels_.setZero(); }

  void configure(const std::string& json) override {
    ComponentParams p(json, kType);
    p.allow_only({"rows", "cols", "size", "pad_from_sensor", "thickness"});
    auto count = [&](const char* key, int fallback) {
      const real n = p.number(key, fallback);
      if (!(n >= 1 && n <= 1024 && n == std::floor(n))) throw Error(p.at(key) + ": expected a whole number from 1 to 1024");
      return static_cast<int>(n);
    };
    const int rows = count("rows", rows_), cols = count("cols", cols_);
    const VecX size = p.vector("size", 2, size_);
    if (!(size.allFinite() && size.minCoeff() > 0)) throw Error(p.at("size") + ": expected two positive lengths (m)");
    const real thickness = p.number("thickness", thickness_);
    if (!(std::isfinite(thickness) && thickness > 0)) throw Error(p.at("thickness") + ": expected a positive length (m)");
    Transform X_SP = X_SP_;
    if (p.has("pad_from_sensor")) {
      const ComponentParams pose(p.json().at("pad_from_sensor").dump(), p.at("pad_from_sensor"));
      pose.allow_only({"rotation", "translation"});
      X_SP.rotation = pose.quaternion("rotation", Quat::Identity());
      X_SP.translation = pose.vec3("translation", Vec3::Zero());
    }
    p.apply_rate(*this);
    rows_ = rows, cols_ = cols, size_ = size, thickness_ = thickness, X_SP_ = X_SP;
    taxels_ = VecX::Zero(rows_ * cols_);
  }

  void update(const Tick&) override {
    taxels_.setZero();
    // the pad frame in the world: link, then sensor, then pad
    const Transform X_PW = (scene_.root_transform(link_) * X_LS_ * X_SP_).inverse();
    for (const physics::ContactPoint& c : scene_.contact_points(link_)) {
      const Vec3 p_P = X_PW * Vec3(c.pos_a);
      const Vec3 f_P = X_PW.rotation * Vec3(c.force);
      if (std::abs(p_P.z()) > thickness_ || !(f_P.z() < 0)) continue;
      // the cell under the point: column along x, row along y
      const real u = (p_P.x() / size_[0] + real(0.5)) * cols_, v = (p_P.y() / size_[1] + real(0.5)) * rows_;
      if (!(u >= 0 && u < cols_ && v >= 0 && v < rows_)) continue;
      taxels_[static_cast<int>(v) * cols_ + static_cast<int>(u)] += -f_P.z();
    }
  }

  VecX signal() const override { return taxels_; }

 private:
  Scene scene_;
  ActorHandle link_;
  Transform X_LS_;  // sensor frame in the link frame
  Transform X_SP_;  // pad frame in the sensor frame
  std::int64_t query_ = 0;
  int rows_ = 8, cols_ = 8;
  VecX size_ = (VecX(2) << real(0.01), real(0.01)).finished();
  real thickness_ = real(0.005);
  VecX taxels_ = VecX::Zero(64);
};

}  // namespace

std::unique_ptr<Component> make_tactile_pad_sensor(const ComponentArgs& args) { return std::make_unique<TactilePadSensor>(args); }

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics
