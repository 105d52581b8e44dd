// Writing a BotPrefab as URDF: links with their inertials and collision shapes, joints with
// their frames, axes, limits, dynamics and mimic couplings. The root joint is left out (a URDF
// root has none). URDF's child link frame is the joint frame, so a link whose frame is offset
// from its joint (joint_from_link) has its inertial, shapes and child joints moved by that offset.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <optional>
#include <set>
#include <sstream>
#include <nlohmann/json.hpp>
#include <tinyxml2.h>

#include "superdex/physics/error.h"
#include "superdex/robotics/bot_prefab.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace fs = std::filesystem;
using physics::JointType;
using physics::Mat3;
using physics::Quat;
using physics::real;
using physics::Vec3;

namespace {

// Shortest text that reads back as the same double.
std::string num(double x) { return nlohmann::json(x).dump(); }

std::string triple(const Vec3& v) { return num(v.x()) + " " + num(v.y()) + " " + num(v.z()); }

// URDF's fixed-axis roll-pitch-yaw: R = Rz(yaw) Ry(pitch) Rx(roll).
std::string rpy(const Quat& q) {
  const Mat3 R = q.normalized().toRotationMatrix();
  const double pitch = std::asin(std::clamp(-double(R(2, 0)), -1.0, 1.0));
  double roll, yaw;
  if (std::abs(R(2, 0)) < 1 - 1e-12) {
    roll = std::atan2(double(R(2, 1)), double(R(2, 2)));
    yaw = std::atan2(double(R(1, 0)), double(R(0, 0)));
  } else {  // gimbal lock: yaw carries the whole rotation about z
    roll = 0;
    yaw = std::atan2(-double(R(0, 1)), double(R(1, 1)));
  }
  return num(roll) + " " + num(pitch) + " " + num(yaw);
}

void origin(tinyxml2::XMLElement* parent, const Vec3& xyz, const Quat& q) {
  auto* o = parent->InsertNewChildElement("origin");
  o->SetAttribute("xyz", triple(xyz).c_str());
  o->SetAttribute("rpy", rpy(q).c_str());
}

struct Writer {
  const BotPrefab& prefab;
  std::vector<std::string>* warnings;
  fs::path mesh_dir;  // empty: meshes are left out (string export)
  std::string mesh_ref_prefix;
  tinyxml2::XMLDocument doc;
  int meshes_written = 0, meshes_skipped = 0, planes_skipped = 0;

  // One <collision> of `shape` at X (in the URDF link frame); a capsule is a cylinder and two balls.
  void collision(tinyxml2::XMLElement* link, const physics::ShapeGeometry& shape, const Vec3& p, const Quat& q, const std::string& stem) {
    auto add = [&](const Vec3& at, const Quat& turn) {
      auto* c = link->InsertNewChildElement("collision");
      origin(c, at, turn);
      return c->InsertNewChildElement("geometry");
    };
    if (const auto* s = std::get_if<physics::SphereShape>(&shape)) {
      add(p + q * s->center, q)->InsertNewChildElement("sphere")->SetAttribute("radius", num(s->radius).c_str());
    } else if (const auto* b = std::get_if<physics::BoxShape>(&shape)) {
      add(p, q)->InsertNewChildElement("box")->SetAttribute("size", triple(2 * b->half_extents).c_str());
    } else if (const auto* c = std::get_if<physics::CapsuleShape>(&shape)) {
      auto* cyl = add(p, q)->InsertNewChildElement("cylinder");
      cyl->SetAttribute("radius", num(c->radius).c_str());
      cyl->SetAttribute("length", num(2 * c->half_length).c_str());
      for (real side : {real(-1), real(1)})
        add(p + q * Vec3(0, 0, side * c->half_length), q)->InsertNewChildElement("sphere")->SetAttribute("radius", num(c->radius).c_str());
    } else if (const auto* m = std::get_if<physics::MeshShape>(&shape)) {
      if (mesh_dir.empty() || !m->mesh) {
        ++meshes_skipped;
        return;
      }
      // the triangles the engine collides with (hull or mesh), as an OBJ beside the URDF
      fs::create_directories(mesh_dir);
      const std::string file = stem + ".obj";
      std::ofstream out(mesh_dir / file);
      if (!out) throw Error((mesh_dir / file).string() + ": cannot write the mesh file");
      out << std::setprecision(17);
      for (const Vec3& v : m->mesh->vertices) out << "v " << v.x() << " " << v.y() << " " << v.z() << "\n";
      for (const auto& t : m->mesh->triangles) out << "f " << t[0] + 1 << " " << t[1] + 1 << " " << t[2] + 1 << "\n";
      add(p, q)->InsertNewChildElement("mesh")->SetAttribute("filename", (mesh_ref_prefix + file).c_str());
      ++meshes_written;
    } else {
      ++planes_skipped;
    }
  }

  std::string write() {
    const auto& a = prefab.articulation;
    const int n = static_cast<int>(a.links.size());
    if (n == 0) throw Error("save_to_urdf: the bot has no links");
    if (a.joints.size() != a.links.size())
      throw Error("save_to_urdf: expected one joint per link (" + std::to_string(n) + " links), got " + std::to_string(a.joints.size()));
    std::vector<std::string> link_name(n), joint_name(n);
    std::set<std::string> used_links, used_joints;
    for (int i = 0; i < n; ++i) {
      link_name[i] = a.links[i].name.empty() ? "link_" + std::to_string(i) : a.links[i].name;
      joint_name[i] = a.joints[i].name.empty() ? "joint_" + std::to_string(i) : a.joints[i].name;
      if (!used_links.insert(link_name[i]).second) throw Error("save_to_urdf: links[" + std::to_string(i) + "].name: duplicate link name '" + link_name[i] + "'");
      if (i > 0 && !used_joints.insert(joint_name[i]).second)
        throw Error("save_to_urdf: joints[" + std::to_string(i) + "].name: duplicate joint name '" + joint_name[i] + "'");
    }
    // where each link's own frame sits in its URDF frame (the joint frame)
    std::vector<Vec3> offset(n, Vec3::Zero());
    for (int i = 1; i < n; ++i) offset[i] = a.links[i].joint_from_link;

    auto* robot = doc.NewElement("robot");
    doc.InsertEndChild(doc.NewDeclaration());
    doc.InsertEndChild(robot);
    robot->SetAttribute("name", a.name.empty() ? "bot" : a.name.c_str());
    std::vector<std::string> no_armature;
    for (int i = 0; i < n; ++i) {
      const physics::LinkDesc& L = a.links[i];
      auto* link = robot->InsertNewChildElement("link");
      link->SetAttribute("name", link_name[i].c_str());
      // the inline primitive at its shapeScale (meshes come baked)
      std::optional<physics::ShapeGeometry> shape;
      if (L.shape) shape = physics::scaled_shape(*L.shape, L.shape_scale, "save_to_urdf: links[" + std::to_string(i) + "].shapeScale");
      // mass and inertia about the centre of mass (the link's axes), from the shape when not given
      real mass = L.mass.value_or(0);
      Vec3 com = L.center_of_mass.value_or(Vec3::Zero());
      std::array<real, 6> I{};
      if (L.moment_of_inertia) {
        I = *L.moment_of_inertia;
      } else if (shape && !std::holds_alternative<physics::PlaneShape>(*shape) && (mass > 0 || !L.mass)) {
        physics::MassProperties mp = physics::shape_mass_properties(*shape, L.density.value_or(real(1000)));
        const Mat3 R = L.link_from_shape.rotation.normalized().toRotationMatrix();
        const Mat3 Ic = R * mp.inertia_about_com * R.transpose() * (L.mass ? mass / mp.mass : real(1));
        if (!L.mass) mass = mp.mass;
        if (!L.center_of_mass) com = L.link_from_shape.rotation.normalized() * mp.center_of_mass + L.link_from_shape.translation;
        I = {Ic(0, 0), Ic(0, 1), Ic(0, 2), Ic(1, 1), Ic(1, 2), Ic(2, 2)};
      }
      if (mass > 0) {
        auto* inertial = link->InsertNewChildElement("inertial");
        origin(inertial, offset[i] + com, Quat::Identity());
        inertial->InsertNewChildElement("mass")->SetAttribute("value", num(mass).c_str());
        auto* inertia = inertial->InsertNewChildElement("inertia");
        const char* names[] = {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"};
        for (int k = 0; k < 6; ++k) inertia->SetAttribute(names[k], num(I[k]).c_str());
      }
      if (shape && L.collider_type != "None")
        collision(link, *shape, offset[i] + L.link_from_shape.translation, L.link_from_shape.rotation, link_name[i]);
      for (size_t k = 0; k < L.extra_shapes.size(); ++k)
        if (L.collider_type != "None")
          collision(link, L.extra_shapes[k].shape, offset[i] + L.extra_shapes[k].link_from_shape.translation,
                    L.extra_shapes[k].link_from_shape.rotation, link_name[i] + "_" + std::to_string(k + 1));
    }
    for (int i = 1; i < n; ++i) {
      const physics::JointDesc& J = a.joints[i];
      const int p = a.links[i].parent_link;
      if (p < 0 || p >= i) throw Error("save_to_urdf: links[" + std::to_string(i) + "].parentLink: must be an earlier link, got " + std::to_string(p));
      auto* joint = robot->InsertNewChildElement("joint");
      joint->SetAttribute("name", joint_name[i].c_str());
      const Vec3 axis = J.axis.norm() > 0 ? Vec3(J.axis.normalized()) : Vec3::UnitZ();
      const bool limited = J.min_limit || J.max_limit;
      std::string type;
      switch (J.type) {
        case JointType::Hard: type = "fixed"; break;
        case JointType::Revolute: type = limited ? "revolute" : "continuous"; break;
        case JointType::Prismatic: type = "prismatic"; break;
        default:
          throw Error("save_to_urdf: joints[" + std::to_string(i) + "].type: URDF has no " + std::string(physics::joint_type_name(J.type)) +
                      " joint below the root (joint '" + joint_name[i] + "')");
      }
      joint->SetAttribute("type", type.c_str());
      origin(joint, offset[p] + J.parent_link_from_joint.translation, J.parent_link_from_joint.rotation);
      joint->InsertNewChildElement("parent")->SetAttribute("link", link_name[p].c_str());
      joint->InsertNewChildElement("child")->SetAttribute("link", link_name[i].c_str());
      if (J.type == JointType::Hard) continue;
      joint->InsertNewChildElement("axis")->SetAttribute("xyz", triple(axis).c_str());
      if (type != "continuous") {
        // a missing side of a limit (or a prismatic joint's missing limits): far away
        constexpr double kFar = 1e10;
        auto* limit = joint->InsertNewChildElement("limit");
        limit->SetAttribute("lower", num(J.min_limit ? double(axis.dot(*J.min_limit)) : -kFar).c_str());
        limit->SetAttribute("upper", num(J.max_limit ? double(axis.dot(*J.max_limit)) : kFar).c_str());
        limit->SetAttribute("effort", num(std::max(double(J.effort_limit), 0.0)).c_str());
        limit->SetAttribute("velocity", "0");
      }
      if (J.viscous_friction > 0 || J.coulomb_friction > 0) {
        auto* dyn = joint->InsertNewChildElement("dynamics");
        dyn->SetAttribute("damping", num(J.viscous_friction).c_str());
        dyn->SetAttribute("friction", num(J.coulomb_friction).c_str());
      }
      if (J.armature > 0) no_armature.push_back(joint_name[i]);
      std::vector<physics::JointCoupling> couplings = a.couplings;
      for (size_t k = 0; k < a.linear_transmissions.size(); ++k)
        if (a.linear_transmissions[k].joint_indices.size() == 2)
          couplings.push_back(physics::coupling_of(a.linear_transmissions[k], a.joints, "save_to_urdf: linearTransmissions[" + std::to_string(k) + "]"));
      for (const physics::JointCoupling& c : couplings)
        if (c.joint == J.name) {
          auto* mimic = joint->InsertNewChildElement("mimic");
          mimic->SetAttribute("joint", c.leader.c_str());
          mimic->SetAttribute("multiplier", num(c.ratio).c_str());
          mimic->SetAttribute("offset", num(c.offset).c_str());
        }
    }
    if (warnings) {
      const std::string who = "save_to_urdf('" + a.name + "'): ";
      if (!no_armature.empty()) {
        std::string list;
        for (const std::string& j : no_armature) list += (list.empty() ? "" : ", ") + j;
        warnings->push_back(who + "URDF has no rotor inertia (armature): left out for joints " + list);
      }
      if (meshes_skipped > 0)
        warnings->push_back(who + std::to_string(meshes_skipped) + " mesh collision shape(s) left out (a URDF string has no folder for mesh files)");
      if (planes_skipped > 0) warnings->push_back(who + std::to_string(planes_skipped) + " plane shape(s) left out (URDF has no plane)");
      if (!a.fixed_tendons.empty()) {
        std::string list;
        for (const physics::FixedTendon& t : a.fixed_tendons) list += (list.empty() ? "" : ", ") + t.name;
        warnings->push_back(who + "URDF has no tendons or joint springs: left out " + list);
      }
    }
    tinyxml2::XMLPrinter printer;
    doc.Print(&printer);
    return printer.CStr();
  }
};

}  // namespace

std::string save_to_urdf_string(const BotPrefab& prefab, std::vector<std::string>* warnings) {
  Writer w{prefab, warnings, {}, {}};
  return w.write();
}

void save_to_urdf_file(const BotPrefab& prefab, const std::string& path, std::vector<std::string>* warnings) {
  const fs::path file = fs::absolute(fs::path(path));
  // meshes go to <stem>_meshes/ beside the file, named relative to it
  const std::string folder = file.stem().string() + "_meshes";
  Writer w{prefab, warnings, file.parent_path() / folder, folder + "/"};
  const std::string xml = w.write();
  std::ofstream out(file);
  if (!out || !(out << xml)) throw Error(path + ": cannot write the URDF file");
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics
