// The PLY reader: a header of `element` and `property` lines, then the records in ASCII (one
// record per line) or binary (little- or big-endian). Only vertex x, y, z and the face index
// list are kept; other elements and properties are read past.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "io/mesh_io_detail.h"
#include "superdex/physics/mesh_io.h"
#include "superdex/physics/mesh_validation.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

using mesh_io::fail;

namespace {

enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };
enum class PlyFormat { Ascii, BinaryLittleEndian, BinaryBigEndian };

bool parse_type(std::string_view name, PlyType& t) {
  static const std::pair<std::string_view, PlyType> kNames[] = {
      {"char", PlyType::Int8},     {"int8", PlyType::Int8},       {"uchar", PlyType::UInt8},     {"uint8", PlyType::UInt8},
      {"short", PlyType::Int16},   {"int16", PlyType::Int16},     {"ushort", PlyType::UInt16},   {"uint16", PlyType::UInt16},
      {"int", PlyType::Int32},     {"int32", PlyType::Int32},     {"uint", PlyType::UInt32},     {"uint32", PlyType::UInt32},
      {"float", PlyType::Float32}, {"float32", PlyType::Float32}, {"double", PlyType::Float64}, {"float64", PlyType::Float64}};
  for (const auto& [n, type] : kNames)
    if (n == name) return t = type, true;
  return false;
}

size_t type_size(PlyType t) {
  switch (t) {
    case PlyType::Int8: case PlyType::UInt8: return 1;
    case PlyType::Int16: case PlyType::UInt16: return 2;
    case PlyType::Int32: case PlyType::UInt32: case PlyType::Float32: return 4;
    case PlyType::Float64: return 8;
  }
  return 0;
}

bool is_integer_type(PlyType t) { return t != PlyType::Float32 && t != PlyType::Float64; }

struct Property {
  std::string name;
  bool is_list = false;
  PlyType count_type = PlyType::UInt8;
  PlyType value_type = PlyType::Float32;
};

struct Element {
  std::string name;
  long long count = 0;
  std::vector<Property> properties;
};

struct Header {
  PlyFormat format = PlyFormat::Ascii;
  std::vector<Element> elements;
  size_t body_offset = 0;  // first byte after the end_header line
  long body_line = 0;      // line number of the first body line (ASCII)
};

Header parse_header(const std::string& path, const std::string& bytes) {
  Header h;
  size_t pos = 0;
  long line_no = 0;
  bool have_format = false, ended = false;
  while (pos < bytes.size() && !ended) {
    size_t end = bytes.find('\n', pos);
    if (end == std::string::npos) end = bytes.size();
    const std::string_view line(bytes.data() + pos, end - pos);
    pos = end + 1;
    ++line_no;
    const auto tok = mesh_io::tokens(line);
    if (line_no == 1) {
      if (tok.size() != 1 || tok[0] != "ply") fail(path, 1, "not a PLY file: the first line must be 'ply'");
      continue;
    }
    if (tok.empty() || tok[0] == "comment" || tok[0] == "obj_info") continue;
    if (tok[0] == "format") {
      if (tok.size() < 2) fail(path, line_no, "'format' needs a format name");
      if (tok[1] == "ascii") h.format = PlyFormat::Ascii;
      else if (tok[1] == "binary_little_endian") h.format = PlyFormat::BinaryLittleEndian;
      else if (tok[1] == "binary_big_endian") h.format = PlyFormat::BinaryBigEndian;
      else fail(path, line_no, "unknown PLY format " + mesh_io::quote(tok[1]) + " (expected ascii, binary_little_endian or binary_big_endian)");
      have_format = true;
    } else if (tok[0] == "element") {
      if (tok.size() != 3) fail(path, line_no, "expected 'element <name> <count>'");
      Element e;
      e.name = std::string(tok[1]);
      if (!mesh_io::parse_integer(tok[2], e.count) || e.count < 0) fail(path, line_no, "malformed element count " + mesh_io::quote(tok[2]));
      h.elements.push_back(std::move(e));
    } else if (tok[0] == "property") {
      if (h.elements.empty()) fail(path, line_no, "'property' before any 'element'");
      Property p;
      if (tok.size() == 5 && tok[1] == "list") {
        p.is_list = true;
        if (!parse_type(tok[2], p.count_type)) fail(path, line_no, "unknown property type " + mesh_io::quote(tok[2]));
        if (!is_integer_type(p.count_type)) fail(path, line_no, "a list count must have an integer type, got " + mesh_io::quote(tok[2]));
        if (!parse_type(tok[3], p.value_type)) fail(path, line_no, "unknown property type " + mesh_io::quote(tok[3]));
        p.name = std::string(tok[4]);
      } else if (tok.size() == 3) {
        if (!parse_type(tok[1], p.value_type)) fail(path, line_no, "unknown property type " + mesh_io::quote(tok[1]));
        p.name = std::string(tok[2]);
      } else {
        fail(path, line_no, "expected 'property <type> <name>' or 'property list <count type> <type> <name>'");
      }
      h.elements.back().properties.push_back(std::move(p));
    } else if (tok[0] == "end_header") {
      ended = true;
    } else {
      fail(path, line_no, "unexpected header line " + mesh_io::quote(line));
    }
  }
  if (!ended) fail(path, 0, "the PLY header has no 'end_header' line");
  if (!have_format) fail(path, 0, "the PLY header has no 'format' line");
  h.body_offset = std::min(pos, bytes.size());
  h.body_line = line_no + 1;
  return h;
}

// Reads the body one value at a time, ASCII or binary, and knows where it is for messages.
class BodyReader {
 public:
  BodyReader(const std::string& path, const std::string& bytes, const Header& h)
      : path_(path), bytes_(bytes), format_(h.format), pos_(h.body_offset), line_(h.body_line - 1) {}

  // Moves to the next record (ASCII: the next non-empty line).
  void begin_record(const Element& e, long long index) {
    element_ = &e;
    index_ = index;
    if (format_ != PlyFormat::Ascii) return;
    tokens_.clear();
    next_token_ = 0;
    while (tokens_.empty()) {
      if (pos_ >= bytes_.size()) fail(path_, 0, "the file ends early, in " + where());
      size_t end = bytes_.find('\n', pos_);
      if (end == std::string::npos) end = bytes_.size();
      tokens_ = mesh_io::tokens(std::string_view(bytes_.data() + pos_, end - pos_));
      pos_ = end + 1;
      ++line_;
    }
  }

  double value(PlyType t) {
    if (format_ == PlyFormat::Ascii) {
      if (next_token_ >= tokens_.size()) fail(path_, line_, "too few values for " + where());
      const std::string_view tok = tokens_[next_token_++];
      double x;
      if (!mesh_io::parse_number(tok, x)) fail(path_, line_, "malformed number " + mesh_io::quote(tok) + " in " + where());
      // integers beyond 32 bits (no PLY integer type holds them), infinity or NaN would not
      // survive the conversions of list lengths and indices
      if (is_integer_type(t) && !(std::isfinite(x) && x == std::floor(x) && std::abs(x) <= 4294967295.0))
        fail(path_, line_, "expected an integer, got " + mesh_io::quote(tok) + " in " + where());
      return x;
    }
    const size_t n = type_size(t);
    if (pos_ + n > bytes_.size()) fail(path_, 0, "the file ends early, in " + where());
    unsigned char b[8];
    std::memcpy(b, bytes_.data() + pos_, n);
    pos_ += n;
    if (format_ == PlyFormat::BinaryBigEndian) std::reverse(b, b + n);
    switch (t) {
      case PlyType::Int8: return static_cast<std::int8_t>(b[0]);
      case PlyType::UInt8: return b[0];
      case PlyType::Int16: { std::int16_t v; std::memcpy(&v, b, 2); return v; }
      case PlyType::UInt16: { std::uint16_t v; std::memcpy(&v, b, 2); return v; }
      case PlyType::Int32: { std::int32_t v; std::memcpy(&v, b, 4); return v; }
      case PlyType::UInt32: { std::uint32_t v; std::memcpy(&v, b, 4); return v; }
      case PlyType::Float32: { float v; std::memcpy(&v, b, 4); return v; }
      case PlyType::Float64: { double v; std::memcpy(&v, b, 8); return v; }
    }
    return 0;
  }

  // The line of the current record (ASCII), 0 for binary files.
  long line() const { return format_ == PlyFormat::Ascii ? line_ : 0; }
  std::string where() const { return "element '" + element_->name + "' record " + std::to_string(index_); }

 private:
  const std::string& path_;
  const std::string& bytes_;
  PlyFormat format_;
  size_t pos_;
  long line_;
  const Element* element_ = nullptr;
  long long index_ = 0;
  std::vector<std::string_view> tokens_;
  size_t next_token_ = 0;
};

}  // namespace

TriangleMesh read_ply_file(const std::string& path) { return read_ply_bytes(mesh_io::read_bytes(path), path); }

TriangleMesh read_ply_bytes(const std::string& bytes, const std::string& path) {
  const Header header = parse_header(path, bytes);
  long long num_vertices = -1;
  for (const Element& e : header.elements)
    if (e.name == "vertex") num_vertices = e.count;
  if (num_vertices < 0) fail(path, 0, "the PLY header declares no 'vertex' element");

  TriangleMesh mesh;
  BodyReader body(path, bytes, header);
  // vertex indices are ints: a larger count declared in the header cannot all be referenced
  const double max_index = static_cast<double>(std::min<long long>(num_vertices, std::numeric_limits<int>::max()));
  for (const Element& e : header.elements) {
    const bool is_vertex = e.name == "vertex", is_face = e.name == "face";
    // another element without properties has nothing to read (an empty line per record in ASCII,
    // no bytes in binary): skipping it keeps a huge declared count from looping without end
    if (e.properties.empty() && !is_vertex && !is_face) continue;
    int xyz[3] = {-1, -1, -1}, index_list = -1;
    for (size_t k = 0; k < e.properties.size(); ++k) {
      const Property& p = e.properties[k];
      if (is_vertex && !p.is_list && p.name.size() == 1 && p.name[0] >= 'x' && p.name[0] <= 'z') xyz[p.name[0] - 'x'] = static_cast<int>(k);
      if (is_face && p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index")) index_list = static_cast<int>(k);
    }
    if (is_vertex)
      for (int a = 0; a < 3; ++a)
        if (xyz[a] < 0) fail(path, 0, std::string("element 'vertex' has no property '") + char('x' + a) + "'");
    if (is_face && index_list < 0) fail(path, 0, "element 'face' has no list property 'vertex_indices'");
    std::vector<int> polygon;
    for (long long r = 0; r < e.count; ++r) {
      body.begin_record(e, r);
      Eigen::Vector3d p = Eigen::Vector3d::Zero();
      polygon.clear();
      for (size_t k = 0; k < e.properties.size(); ++k) {
        const Property& prop = e.properties[k];
        if (!prop.is_list) {
          const double v = body.value(prop.value_type);
          for (int a = 0; a < 3; ++a)
            if (xyz[a] == static_cast<int>(k)) p[a] = v;
          continue;
        }
        const double n = body.value(prop.count_type);
        if (n < 0) fail(path, body.line(), "negative list length in " + body.where());
        for (long long i = 0; i < static_cast<long long>(n); ++i) {
          const double v = body.value(prop.value_type);
          if (static_cast<int>(k) != index_list) continue;
          if (!(v >= 0 && v < max_index))
            fail(path, body.line(), "face " + std::to_string(r) + " has vertex index " + std::to_string(static_cast<long long>(v)) +
                                        " out of range: the file has " + std::to_string(num_vertices) + " vertices");
          polygon.push_back(static_cast<int>(v));
        }
      }
      if (is_vertex) {
        if (!p.allFinite()) fail(path, body.line(), "vertex " + std::to_string(r) + " has a non-finite coordinate (NaN or infinity)");
        mesh.vertices.push_back(p.cast<real>());
      }
      if (is_face) {
        if (polygon.size() < 3) fail(path, body.line(), "face " + std::to_string(r) + " needs at least 3 vertices, got " + std::to_string(polygon.size()));
        mesh_io::add_fan(mesh, polygon);
      }
    }
  }
  // exporters leave slivers: they are dropped with a warning, other defects are errors
  remove_degenerate_triangles(mesh, path);
  check_triangle_mesh(mesh, path);
  return mesh;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
