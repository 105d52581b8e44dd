#include "import/mjcf_document.h"

#include <cctype>
#include <cmath>

#include "import/import_support.h"
#include "superdex/physics/error.h"
#include "superdex/physics/file_path.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace fs = std::filesystem;
using tinyxml2::XMLElement;

namespace {

// More includes than this are taken for a file that includes itself.
constexpr int kMaxIncludes = 1000;

}  // namespace

MjcfDocument::MjcfDocument(const std::string& path, std::vector<std::string>* warnings)
    : path_(path), dir_(fs::absolute(fs::path(path)).parent_path()), warnings_(warnings) {
  if (!is_existing_file(path_)) fail_file("cannot open the MJCF file (does it exist?)");
  if (doc_.LoadFile(path_.c_str()) != tinyxml2::XML_SUCCESS)
    fail_file("not a valid XML file: " + std::string(doc_.ErrorStr() ? doc_.ErrorStr() : doc_.ErrorName()));
  root_ = doc_.RootElement();
  if (!root_ || std::string(root_->Name()) != "mujoco")
    fail_file(std::string("not an MJCF file: the root element is <") + (root_ ? root_->Name() : "") + ">, expected <mujoco>");
  expand_includes(root_, dir_);
  defaults_["main"];
  read_compiler();
  for (const XMLElement* d = root_->FirstChildElement("default"); d; d = d->NextSiblingElement("default")) read_defaults(d, "");
}

// ---------------------------------------------------------------------------- messages

std::string MjcfDocument::label(const XMLElement* e) {
  std::string out;
  for (const XMLElement* k = e; k; k = k->Parent() ? k->Parent()->ToElement() : nullptr) {
    std::string part = std::string("<") + k->Name();
    if (const char* n = k->Attribute("name")) part += " name=" + in_quotes(n);
    else if (const char* c = k->Attribute("class")) part += " class=" + in_quotes(c);
    part += ">";
    out = out.empty() ? part : part + "/" + out;
    const std::string tag = k->Name();
    if (tag == "body" || tag == "worldbody" || tag == "mujoco" || tag == "asset" || tag == "default") break;
  }
  return out;
}

void MjcfDocument::fail(const XMLElement* e, const std::string& what) const {
  const int line = e->GetLineNum();
  throw Error(path_ + ": " + (line > 0 ? "line " + std::to_string(line) + ": " : "") + label(e) + ": " + what);
}
void MjcfDocument::fail_file(const std::string& what) const { throw Error(path_ + ": " + what); }
void MjcfDocument::warn(const XMLElement* e, const std::string& what) const {
  if (!warnings_) return;
  const int line = e->GetLineNum();
  warnings_->push_back(path_ + ": " + (line > 0 ? "line " + std::to_string(line) + ": " : "") + label(e) + ": " + what);
}

// ---------------------------------------------------------------------------- includes

namespace {
// The first <include> element below `e` in document order, or nullptr.
XMLElement* first_include(XMLElement* e) {
  for (XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    if (std::string(c->Name()) == "include") return c;
    if (XMLElement* inner = first_include(c)) return inner;
  }
  return nullptr;
}
}  // namespace

// Replaces each <include file="..."> (a path relative to the main model's folder, as in MuJoCo)
// by the children of the included file's root element, until none is left.
void MjcfDocument::expand_includes(XMLElement* top, const fs::path& dir) {
  int expanded = 0;
  while (XMLElement* e = first_include(top)) {
    if (++expanded > kMaxIncludes) fail(e, "more than " + std::to_string(kMaxIncludes) + " includes (a file including itself?)");
    const char* file = e->Attribute("file");
    if (!file || !*file) fail(e, "missing required attribute 'file'");
    fs::path p(file);
    if (p.is_relative()) p = dir / p;
    tinyxml2::XMLDocument inc;
    if (!is_existing_file(p.string())) fail(e, "included file " + in_quotes(p.string()) + " not found");
    if (inc.LoadFile(p.string().c_str()) != tinyxml2::XML_SUCCESS)
      fail(e, "included file " + in_quotes(p.string()) + " is not valid XML: " + (inc.ErrorStr() ? inc.ErrorStr() : inc.ErrorName()));
    const XMLElement* root = inc.RootElement();
    // the root is <mujoco> (or the older <mujocoinclude>): its children are what is included
    if (!root) fail(e, "included file " + in_quotes(p.string()) + " has no root element");
    tinyxml2::XMLNode* parent = e->Parent();
    tinyxml2::XMLNode* after = e;
    for (const XMLElement* c = root->FirstChildElement(); c; c = c->NextSiblingElement()) after = parent->InsertAfterChild(after, c->DeepClone(&doc_));
    parent->DeleteChild(e);
  }
}

// ---------------------------------------------------------------------------- defaults

void MjcfDocument::read_defaults(const XMLElement* def, const std::string& parent_class) {
  const char* cls = def->Attribute("class");
  const std::string name = cls ? cls : (parent_class.empty() ? "main" : "");
  if (name.empty()) fail(def, "a nested <default> needs a 'class'");
  if (!parent_class.empty()) {
    if (defaults_.count(name) && name != "main") fail(def, "duplicate default class " + in_quotes(name));
    defaults_[name] = defaults_[parent_class];
  }
  auto& sets = defaults_[name];
  for (const XMLElement* c = def->FirstChildElement(); c; c = c->NextSiblingElement()) {
    const std::string kind = c->Name();
    if (kind == "default") continue;
    auto& set = sets[kind];
    for (const tinyxml2::XMLAttribute* a = c->FirstAttribute(); a; a = a->Next()) set[a->Name()] = a->Value();
  }
  for (const XMLElement* c = def->FirstChildElement("default"); c; c = c->NextSiblingElement("default")) read_defaults(c, name);
}

std::string MjcfDocument::child_class(const XMLElement* e, const std::string& inherited) const {
  const char* c = e->Attribute("childclass");
  if (!c) return inherited;
  if (!defaults_.count(c)) fail(e, "childclass " + in_quotes(c) + " is not a defined default class");
  return c;
}

const char* MjcfDocument::attr(const XMLElement* e, const char* name, const std::string& childclass) const {
  if (const char* v = e->Attribute(name)) return v;
  const char* own = e->Attribute("class");
  const std::string cls = own ? own : (childclass.empty() ? "main" : childclass);
  const auto c = defaults_.find(cls);
  if (c == defaults_.end()) fail(e, "class " + in_quotes(cls) + " is not a defined default class");
  // <fixed> and <spatial> tendons take their defaults from <default><tendon>
  const std::string kind = e->Name();
  const auto k = c->second.find(kind == "fixed" || kind == "spatial" ? std::string("tendon") : kind);
  if (k == c->second.end()) return nullptr;
  const auto a = k->second.find(name);
  return a == k->second.end() ? nullptr : a->second.c_str();
}

std::optional<std::vector<double>> MjcfDocument::numbers(const XMLElement* e, const char* name, const std::string& childclass,
                                                         size_t count) const {
  const char* v = attr(e, name, childclass);
  if (!v) return std::nullopt;
  std::string bad;
  auto out = parse_numbers(v, &bad);
  if (!out) fail(e, std::string("attribute '") + name + "': malformed number '" + bad + "' in \"" + v + "\"");
  if (out->empty() || (count && out->size() != count))
    fail(e, std::string("attribute '") + name + "': expected " + (count ? std::to_string(count) : "at least one") + " number" +
                (count == 1 ? "" : "s") + ", got \"" + v + "\"");
  return out;
}

double MjcfDocument::number_or(const XMLElement* e, const char* name, const std::string& childclass, double fallback) const {
  const auto v = numbers(e, name, childclass, 1);
  return v ? (*v)[0] : fallback;
}

Eigen::Vector3d MjcfDocument::vec3_or(const XMLElement* e, const char* name, const std::string& childclass,
                                      const Eigen::Vector3d& fallback) const {
  const auto v = numbers(e, name, childclass, 3);
  return v ? Eigen::Vector3d((*v)[0], (*v)[1], (*v)[2]) : fallback;
}

std::optional<bool> MjcfDocument::boolean(const XMLElement* e, const char* name, const std::string& childclass) const {
  const char* v = attr(e, name, childclass);
  if (!v) return std::nullopt;
  const std::string s = v;
  if (s == "true") return true;
  if (s == "false") return false;
  if (s == "auto") return std::nullopt;
  fail(e, std::string("attribute '") + name + "': expected true, false or auto, got \"" + s + "\"");
}

// ---------------------------------------------------------------------------- frames

Eigen::Quaterniond MjcfDocument::z_to(const Eigen::Vector3d& v) {
  const Eigen::Vector3d z = v.normalized();
  // antiparallel: half a turn about x
  if (z.z() < -1 + 1e-14) return Eigen::Quaterniond(0, 1, 0, 0);
  return Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), z);
}

Eigen::Quaterniond MjcfDocument::orientation(const XMLElement* e, const std::string& childclass) const {
  int given = 0;
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  if (const auto v = numbers(e, "quat", childclass, 4)) {
    ++given;
    q = Eigen::Quaterniond((*v)[0], (*v)[1], (*v)[2], (*v)[3]);
    if (q.norm() < 1e-14) fail(e, "attribute 'quat' must not be zero");
    q.normalize();
  }
  if (const auto v = numbers(e, "axisangle", childclass, 4)) {
    ++given;
    const Eigen::Vector3d axis((*v)[0], (*v)[1], (*v)[2]);
    if (axis.norm() < 1e-14) fail(e, "attribute 'axisangle': the axis must not be zero");
    q = Eigen::Quaterniond(Eigen::AngleAxisd(angle((*v)[3]), axis.normalized()));
  }
  if (const auto v = numbers(e, "euler", childclass, 3)) {
    ++given;
    const std::string& seq = compiler_.eulerseq;
    q = Eigen::Quaterniond::Identity();
    for (int i = 0; i < 3; ++i) {
      const char c = seq[i];
      const int axis = std::tolower(static_cast<unsigned char>(c)) - 'x';
      const Eigen::Quaterniond r(Eigen::AngleAxisd(angle((*v)[i]), Eigen::Vector3d::Unit(axis)));
      // lower case: about the moving frame's axis (intrinsic), upper case: the fixed one
      q = std::islower(static_cast<unsigned char>(c)) ? q * r : r * q;
    }
  }
  if (const auto v = numbers(e, "xyaxes", childclass, 6)) {
    ++given;
    Eigen::Vector3d x((*v)[0], (*v)[1], (*v)[2]), y((*v)[3], (*v)[4], (*v)[5]);
    if (x.norm() < 1e-14) fail(e, "attribute 'xyaxes': the x axis must not be zero");
    x.normalize();
    y -= x * x.dot(y);
    if (y.norm() < 1e-14) fail(e, "attribute 'xyaxes': the y axis must not be parallel to the x axis");
    y.normalize();
    Eigen::Matrix3d R;
    R << x, y, x.cross(y);
    q = Eigen::Quaterniond(R);
  }
  if (const auto v = numbers(e, "zaxis", childclass, 3)) {
    ++given;
    const Eigen::Vector3d z((*v)[0], (*v)[1], (*v)[2]);
    if (z.norm() < 1e-14) fail(e, "attribute 'zaxis' must not be zero");
    q = z_to(z);
  }
  if (given > 1) fail(e, "give at most one of quat, axisangle, euler, xyaxes and zaxis");
  return q;
}

Eigen::Isometry3d MjcfDocument::pose(const XMLElement* e, const std::string& childclass) const {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = orientation(e, childclass).toRotationMatrix();
  X.translation() = vec3_or(e, "pos", childclass, Eigen::Vector3d::Zero());
  return X;
}

// ---------------------------------------------------------------------------- compiler

void MjcfDocument::read_compiler() {
  for (const XMLElement* c = root_->FirstChildElement("compiler"); c; c = c->NextSiblingElement("compiler")) {
    if (const char* a = c->Attribute("angle")) {
      const std::string s = a;
      if (s != "degree" && s != "radian") fail(c, "attribute 'angle': expected degree or radian, got \"" + s + "\"");
      compiler_.degrees = s == "degree";
    }
    if (const char* s = c->Attribute("eulerseq")) {
      const std::string seq = s;
      bool ok = seq.size() == 3;
      for (char ch : seq) ok &= std::string("xyzXYZ").find(ch) != std::string::npos;
      if (!ok) fail(c, "attribute 'eulerseq': expected three of x, y, z, X, Y, Z, got \"" + seq + "\"");
      compiler_.eulerseq = seq;
    }
    if (const char* s = c->Attribute("coordinate"); s && std::string(s) != "local")
      fail(c, "coordinate=\"" + std::string(s) + "\" is not supported (MuJoCo itself dropped it): only local coordinates");
    if (const char* s = c->Attribute("assetdir")) compiler_.meshdir = s;
    if (const char* s = c->Attribute("meshdir")) compiler_.meshdir = s;
    if (const auto b = boolean(c, "autolimits", "")) compiler_.autolimits = *b;
    if (const char* s = c->Attribute("inertiafromgeom")) {
      const std::string v = s;
      if (v != "auto" && v != "true" && v != "false") fail(c, "attribute 'inertiafromgeom': expected auto, true or false, got \"" + v + "\"");
      compiler_.inertiafromgeom = v;
    }
    if (const auto r = numbers(c, "inertiagrouprange", "", 2)) {
      compiler_.inertia_group_min = static_cast<int>((*r)[0]);
      compiler_.inertia_group_max = static_cast<int>((*r)[1]);
    }
    compiler_.boundmass = number_or(c, "boundmass", "", compiler_.boundmass);
    compiler_.boundinertia = number_or(c, "boundinertia", "", compiler_.boundinertia);
    if (const auto b = boolean(c, "balanceinertia", "")) compiler_.balanceinertia = *b;
    if (const auto m = numbers(c, "settotalmass", "", 1); m && (*m)[0] > 0) compiler_.settotalmass = (*m)[0];
    if (const auto b = boolean(c, "discardvisual", ""); b && *b)
      warn(c, "discardvisual is ignored: visual-only geoms are kept (they never collide, and give mass as in MuJoCo's default)");
  }
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics
