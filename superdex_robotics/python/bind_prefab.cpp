// BotPrefab and its links, joints and component declarations, editable from Python before
// create_bot. Lists are bound by reference: prefab.links[2].mass = 3.0 edits the prefab.

#include <nanobind/stl/bind_vector.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>

#include "superdex/robotics/bot_prefab.h"

// lists bound by reference (not converted to Python lists), so that edits reach the prefab
NB_MAKE_OPAQUE(std::vector<superdex::physics::LinkDesc>)
NB_MAKE_OPAQUE(std::vector<superdex::physics::JointDesc>)
NB_MAKE_OPAQUE(std::vector<superdex::robotics::ComponentDecl>)
NB_MAKE_OPAQUE(std::vector<std::vector<superdex::robotics::ComponentDecl>>)
NB_MAKE_OPAQUE(std::vector<superdex::robotics::BotSensorPrefab>)
NB_MAKE_OPAQUE(std::vector<superdex::robotics::BotActuatorPrefab>)
NB_MAKE_OPAQUE(std::vector<superdex::physics::JointCoupling>)
NB_MAKE_OPAQUE(std::vector<superdex::physics::LinearTransmission>)


#include "bind_common.h"
#include "bind_container.h"
#include "struct_binder.h"

namespace superdex::python {

using robotics::BotPrefab;
using robotics::BotActuatorPrefab;
using robotics::BotLinkPrefab;
using robotics::BotSensorPrefab;
using robotics::ComponentDecl;

namespace {

nb::object optional_vec3(const std::optional<Vec3>& v) { return v ? nb::cast(numpy_copy(v->data(), {3})) : nb::none(); }
std::optional<Vec3> read_optional_vec3(nb::handle h, const char* what) {
  if (h.is_none()) return std::nullopt;
  return read_vec3(h, what);
}

// Keyword construction through the bound properties (their conversions and checks), on an
// instance built aside so that a rejected keyword leaves nothing half-made.
template <class T>
void init_from_kwargs(T* self, const nb::kwargs& kwargs, const std::string& type_name) {
  T t;
  {
    nb::object view = nb::cast(&t, nb::rv_policy::reference);
    for (auto [key, value] : kwargs) {
      const std::string k = nb::cast<std::string>(key);
      if (k.empty() || k[0] == '_' || !nb::hasattr(view.type(), k.c_str()))
        throw Error(type_name + "(): unknown field '" + k + "'");
      try {
        nb::setattr(view, k.c_str(), value);
      } catch (nb::python_error& e) {
        throw Error(type_name + "(): " + k + ": " + e.what());
      }
    }
  }
  new (self) T(std::move(t));
}

// A list of T from any iterable of T; Error names `what` and the index of a wrong element.
template <class T>
std::vector<T> list_of(nb::handle items, const std::string& what, const char* expected) {
  if (!nb::isinstance<nb::iterable>(items) || nb::isinstance<nb::str>(items)) throw Error(what + ": expected a list of " + expected);
  std::vector<T> out;
  size_t i = 0;
  for (nb::handle item : nb::iter(items)) {
    T* p = nullptr;
    if (!nb::try_cast<T*>(item, p) || !p)
      throw Error(what + "[" + std::to_string(i) + "]: expected a " + expected + ", got " + nb::inst_name(item).c_str());
    out.push_back(*p);
    ++i;
  }
  return out;
}

}  // namespace

void export_prefab(nb::module_& m) {
  nb::class_<ComponentDecl>(m, "ComponentDecl", "A sensor or actuator declared on a link.")
      .def(nb::init<>())
      .def("__init__", [](ComponentDecl* d, std::string type, std::string name, std::string params) {
             new (d) ComponentDecl{std::move(type), std::move(name), std::move(params), {}};
           }, "type"_a, "name"_a, "params"_a = "")
      .def_rw("type", &ComponentDecl::type)
      .def_rw("name", &ComponentDecl::name)
      .def_rw("params", &ComponentDecl::params)
      .def("__repr__", [](const ComponentDecl& d) { return "ComponentDecl(type='" + d.type + "', name='" + d.name + "')"; });
  nb::bind_vector<std::vector<ComponentDecl>, nb::rv_policy::reference_internal>(m, "ComponentDeclList");

  StructBinder<BotSensorPrefab>(m, "BotSensorPrefab", "A sensor declared on a link (BotLinkPrefab.sensors).")
      .field("type", &BotSensorPrefab::type, "registered sensor type, e.g. \"SENSOR_CAMERA\"")
      .field("name", &BotSensorPrefab::name, "instance name")
      .field("parent_from_sensor", &BotSensorPrefab::parent_from_sensor, "the sensor frame in the link frame")
      .field("params", &BotSensorPrefab::params, "inline JSON, a JSON file path relative to the bot file, or empty")
      .done();
  StructBinder<BotActuatorPrefab>(m, "BotActuatorPrefab", "An actuator declared on a link (BotLinkPrefab.actuators).")
      .field("type", &BotActuatorPrefab::type, "registered actuator type")
      .field("name", &BotActuatorPrefab::name, "instance name")
      .field("params", &BotActuatorPrefab::params, "inline JSON, a JSON file path relative to the bot file, or empty")
      .done();
  StructBinder<physics::JointCoupling>(m, "JointCoupling",
                                       "A joint that follows another: q_joint = ratio q_leader + offset (BotPrefab.couplings).")
      .field("joint", &physics::JointCoupling::joint, "the follower's name")
      .field("leader", &physics::JointCoupling::leader, "the name of the joint it follows")
      .field("ratio", &physics::JointCoupling::ratio, "(rad or m) per (rad or m)")
      .field("offset", &physics::JointCoupling::offset, "rad or m")
      .done();
  nb::bind_vector<std::vector<physics::JointCoupling>, nb::rv_policy::reference_internal>(m, "DynamicArrayJointCoupling");
  StructBinder<physics::LinearTransmission>(m, "BotLinearTransmissionPrefab",
                                            "A linear transmission between joints (BotPrefab.linear_transmissions): sum_k c_k q_k driven "
                                            "towards target_displacement. One of two joints is held as a rigid coupling (the second joint "
                                            "follows the first by -c_0 / c_1); its spring and damper are not modelled yet.")
      .field("name", &physics::LinearTransmission::name, "a label")
      .field("joint_indices", &physics::LinearTransmission::joint_indices, "indices into BotPrefab.joints")
      .field("joint_coefficients", &physics::LinearTransmission::joint_coefficients, "c_k per joint")
      .field("joint_axis_disps", &physics::LinearTransmission::joint_axis_disps, "attachment offsets along the joint axes (m)")
      .field("target_displacement", &physics::LinearTransmission::target_displacement, "m (or joint units for a gearbox)")
      .field("stiffness", &physics::LinearTransmission::stiffness, "N/m (not modelled yet)")
      .field("damping", &physics::LinearTransmission::damping, "N s/m (not modelled yet)")
      .field("allow_compressive_force", &physics::LinearTransmission::allow_compressive_force)
      .done();
  nb::bind_vector<std::vector<physics::LinearTransmission>, nb::rv_policy::reference_internal>(m, "DynamicArrayBotLinearTransmissionPrefab");
  StructBinder<physics::FixedTendon>(m, "FixedTendon",
                                     "A fixed tendon (BotPrefab.fixed_tendons, MJCF <tendon><fixed>): length L = sum_k c_k q_k, kept "
                                     "within [lower, upper] where limited, pulled towards rest_length by a spring and damper.")
      .field("name", &physics::FixedTendon::name)
      .field("joints", &physics::FixedTendon::joints, "joint names, one per coefficient")
      .field("coefficients", &physics::FixedTendon::coefficients, "c_k: length per unit of joint k's motion")
      .field("has_lower", &physics::FixedTendon::has_lower)
      .field("has_upper", &physics::FixedTendon::has_upper)
      .field("lower", &physics::FixedTendon::lower, "m (or rad), where has_lower")
      .field("upper", &physics::FixedTendon::upper, "m (or rad), where has_upper")
      .field("stiffness", &physics::FixedTendon::stiffness, "N/m (or N m/rad)")
      .field("damping", &physics::FixedTendon::damping, "N s/m (or N m s/rad)")
      .field("rest_length", &physics::FixedTendon::rest_length, "m (or rad): the spring's relaxed length")
      .done();
  nb::bind_vector<std::vector<physics::FixedTendon>, nb::rv_policy::reference_internal>(m, "DynamicArrayFixedTendon");
  nb::bind_vector<std::vector<BotSensorPrefab>, nb::rv_policy::reference_internal>(m, "DynamicArrayBotSensorPrefab");
  nb::bind_vector<std::vector<BotActuatorPrefab>, nb::rv_policy::reference_internal>(m, "DynamicArrayBotActuatorPrefab");
  nb::bind_vector<std::vector<std::vector<ComponentDecl>>, nb::rv_policy::reference_internal>(m, "ComponentDeclLists");

  nb::class_<LinkDesc>(m, "LinkDesc", "One link of a bot (fields of the .superdex_bot format).")
      .def(nb::init<>())
      .def("__init__", [](LinkDesc* self, nb::kwargs kw) { init_from_kwargs(self, kw, "LinkDesc"); })
      .def_rw("name", &LinkDesc::name)
      .def_rw("parent_link", &LinkDesc::parent_link, "index of the parent link, -1 for the root")
      .def_rw("mass", &LinkDesc::mass, "kg, or None to compute it from density and shape")
      .def_prop_rw("center_of_mass", [](const LinkDesc& l) { return optional_vec3(l.center_of_mass); },
                   [](LinkDesc& l, nb::handle v) { l.center_of_mass = read_optional_vec3(v, "center_of_mass"); })
      .def_prop_rw("moment_of_inertia",
                   [](const LinkDesc& l) -> nb::object {
                     if (!l.moment_of_inertia) return nb::none();
                     return nb::cast(numpy_copy(l.moment_of_inertia->data(), {6}));
                   },
                   [](LinkDesc& l, nb::handle v) {
                     if (v.is_none()) return l.moment_of_inertia.reset();
                     const VecX x = read_vector(v, "moment_of_inertia", 6);
                     l.moment_of_inertia = std::array<real, 6>{x[0], x[1], x[2], x[3], x[4], x[5]};
                   }, "Ixx, Ixy, Ixz, Iyy, Iyz, Izz about the COM in the link frame (kg m^2)")
      .def_rw("density", &LinkDesc::density)
      .def_rw("has_gravity", &LinkDesc::has_gravity)
      .def_rw("layer", &LinkDesc::layer)
      .def_rw("render_model", &LinkDesc::render_model)
      .def_rw("contact", &LinkDesc::contact, "its contact params")
      .def("__repr__", [](const LinkDesc& l) { return "LinkDesc('" + l.name + "')"; });
  nb::bind_vector<std::vector<LinkDesc>, nb::rv_policy::reference_internal>(m, "LinkDescList");

  nb::class_<JointDesc>(m, "JointDesc", "One joint of a bot (fields of the .superdex_bot format); SuperDex API name BotJointPrefab.")
      .def(nb::init<>())
      .def("__init__", [](JointDesc* self, nb::kwargs kw) { init_from_kwargs(self, kw, "BotJointPrefab"); })
      .def_rw("name", &JointDesc::name)
      .def_rw("type", &JointDesc::type)
      .def_prop_rw("axis", [](const JointDesc& j) { return numpy_copy(j.axis.data(), {3}); },
                   [](JointDesc& j, nb::handle v) { j.axis = read_vec3(v, "axis"); }, nb::rv_policy::automatic)
      .def_prop_rw("parent_link_from_joint", [](const JointDesc& j) { return j.parent_link_from_joint; },
                   [](JointDesc& j, nb::handle t) { j.parent_link_from_joint = read_transform(t, "parent_link_from_joint"); })
      .def_prop_rw("min_limit", [](const JointDesc& j) { return optional_vec3(j.min_limit); },
                   [](JointDesc& j, nb::handle v) { j.min_limit = read_optional_vec3(v, "min_limit"); })
      .def_prop_rw("max_limit", [](const JointDesc& j) { return optional_vec3(j.max_limit); },
                   [](JointDesc& j, nb::handle v) { j.max_limit = read_optional_vec3(v, "max_limit"); })
      .def_rw("effort_limit", &JointDesc::effort_limit)
      .def_rw("coulomb_friction", &JointDesc::coulomb_friction)
      .def_rw("viscous_friction", &JointDesc::viscous_friction)
      .def_rw("armature", &JointDesc::armature)
      .def_rw("limit_stiffness", &JointDesc::limit_stiffness)
      .def_rw("limit_damping", &JointDesc::limit_damping)
      .def("__repr__", [](const JointDesc& j) { return "JointDesc('" + j.name + "')"; });
  nb::bind_vector<std::vector<JointDesc>, nb::rv_policy::reference_internal>(m, "JointDescList");

  nb::class_<BotLinkPrefab, LinkDesc>(m, "BotLinkPrefab", "A link with the sensors and actuators declared on it (BotPrefab.add_link).")
      .def(nb::init<>())
      .def("__init__", [](BotLinkPrefab* self, nb::kwargs kw) { init_from_kwargs(self, kw, "BotLinkPrefab"); })
      .def_prop_rw("sensors", [](BotLinkPrefab& l) -> std::vector<BotSensorPrefab>& { return l.sensors; },
                   [](BotLinkPrefab& l, nb::handle v) { l.sensors = list_of<BotSensorPrefab>(v, "BotLinkPrefab.sensors", "BotSensorPrefab"); },
                   nb::rv_policy::reference_internal, "sensors declared on this link")
      .def_prop_rw("actuators", [](BotLinkPrefab& l) -> std::vector<BotActuatorPrefab>& { return l.actuators; },
                   [](BotLinkPrefab& l, nb::handle v) {
                     l.actuators = list_of<BotActuatorPrefab>(v, "BotLinkPrefab.actuators", "BotActuatorPrefab");
                   }, nb::rv_policy::reference_internal, "actuators declared on this link")
      .def("__repr__", [](const BotLinkPrefab& l) {
        return "BotLinkPrefab('" + l.name + "', " + std::to_string(l.sensors.size()) + " sensors, " +
               std::to_string(l.actuators.size()) + " actuators)";
      });

  nb::class_<BotPrefab>(m, "BotPrefab", "A robot description; edit it before create_bot.")
      .def(nb::init<>(), "An empty bot: add links with add_link.")
      .def("add_link", [](BotPrefab& p, nb::handle link, nb::handle joint) {
             robotics::add_link(p, object_of<BotLinkPrefab>(link, "add_link: link", "a BotLinkPrefab"),
                                joint.is_none() ? JointDesc{} : object_of<JointDesc>(joint, "add_link: joint", "a BotJointPrefab"));
           }, "link"_a.none(), "joint"_a.none(),
           "Appends a link, the joint attaching it to link.parent_link (the world for the first link), and\n"
           "the sensors and actuators declared on it.")
      .def("get_link_prefab", [](const BotPrefab& p, int i) { return robotics::link_prefab(p, i); }, "index"_a,
           "A copy of link `index` with the sensors and actuators declared on it.")
      .def_prop_rw("name", [](const BotPrefab& p) { return p.articulation.name; },
                   [](BotPrefab& p, std::string n) { p.articulation.name = std::move(n); })
      .def_prop_rw("links", [](BotPrefab& p) -> std::vector<LinkDesc>& { return p.articulation.links; },
                   [](BotPrefab& p, std::vector<LinkDesc> links) {
                     p.articulation.links = std::move(links);
                     // one (possibly empty) list of sensors and of actuators per link
                     p.sensors.resize(p.articulation.links.size());
                     p.actuators.resize(p.articulation.links.size());
                   },
                   nb::rv_policy::reference_internal, "the links (editable in place or replaced; one joint per link)")
      .def_prop_rw("joints", [](BotPrefab& p) -> std::vector<JointDesc>& { return p.articulation.joints; },
                   [](BotPrefab& p, std::vector<JointDesc> joints) { p.articulation.joints = std::move(joints); },
                   nb::rv_policy::reference_internal, "joints[i] attaches links[i] to its parent")
      .def_prop_rw("default_pose", [](const BotPrefab& p) { return p.articulation.default_pose; },
                   [](BotPrefab& p, nb::handle v) {
                     const VecX x = read_vector(v, "default_pose");
                     p.articulation.default_pose.assign(x.data(), x.data() + x.size());
                   }, "joint positions in DOF order after the root joint's DOFs")
      .def_prop_rw("world_from_root", [](const BotPrefab& p) { return p.articulation.world_from_root; },
                   [](BotPrefab& p, nb::handle t) { p.articulation.world_from_root = read_transform(t, "world_from_root"); })
      .def_prop_rw("couplings", [](BotPrefab& p) -> std::vector<physics::JointCoupling>& { return p.articulation.couplings; },
                   [](BotPrefab& p, std::vector<physics::JointCoupling> c) { p.articulation.couplings = std::move(c); },
                   nb::rv_policy::reference_internal, "joints that follow others (URDF <mimic>, MJCF joint equalities)")
      .def_prop_rw("linear_transmissions",
                   [](BotPrefab& p) -> std::vector<physics::LinearTransmission>& { return p.articulation.linear_transmissions; },
                   [](BotPrefab& p, std::vector<physics::LinearTransmission> t) { p.articulation.linear_transmissions = std::move(t); },
                   nb::rv_policy::reference_internal, "the bot file's linearTransmissions (two-joint ones hold their joints coupled)")
      .def_prop_rw("fixed_tendons", [](BotPrefab& p) -> std::vector<physics::FixedTendon>& { return p.articulation.fixed_tendons; },
                   [](BotPrefab& p, std::vector<physics::FixedTendon> t) { p.articulation.fixed_tendons = std::move(t); },
                   nb::rv_policy::reference_internal, "fixed tendons: length limits and springs on sums of joint positions (MJCF)")
      .def_prop_ro("sensors", [](BotPrefab& p) -> std::vector<std::vector<ComponentDecl>>& { return p.sensors; },
                   nb::rv_policy::reference_internal, "per link: the sensors declared on it")
      .def_prop_ro("actuators", [](BotPrefab& p) -> std::vector<std::vector<ComponentDecl>>& { return p.actuators; },
                   nb::rv_policy::reference_internal, "per link: the actuators declared on it")
      .def_ro("source", &BotPrefab::source)
      .def("__repr__", [](const BotPrefab& p) {
        return "BotPrefab('" + p.articulation.name + "', " + std::to_string(p.articulation.links.size()) + " links)";
      });
}

}  // namespace superdex::python
