#pragma once
// Field checks of the params structs: each throws superdex::Error "<where>.<field>: <what>, got <value>".

#include <cmath>
#include <string>

#include "superdex/physics/error.h"
#include "superdex/physics/real.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

inline std::string value_text(double x) {
  std::string s = std::to_string(x);
  if (s.find('.') != std::string::npos) {
    while (!s.empty() && s.back() == '0') s.pop_back();
    if (!s.empty() && s.back() == '.') s.pop_back();
  }
  return s;
}

class FieldCheck {
 public:
  explicit FieldCheck(std::string where) : where_(std::move(where)) {}
  [[noreturn]] void fail(const std::string& field, const std::string& what) const { throw Error(where_ + "." + field + ": " + what); }
  void finite(const std::string& field, double x) const {
    if (!std::isfinite(x)) fail(field, "must be finite, got " + value_text(x));
  }
  void positive(const std::string& field, double x) const {
    if (!(std::isfinite(x) && x > 0)) fail(field, "must be a positive finite number, got " + value_text(x));
  }
  void non_negative(const std::string& field, double x) const {
    if (!(std::isfinite(x) && x >= 0)) fail(field, "must be a finite number >= 0, got " + value_text(x));
  }
  void in_range(const std::string& field, double x, double lo, double hi) const {
    if (!(std::isfinite(x) && x >= lo && x <= hi))
      fail(field, "must be in [" + value_text(lo) + ", " + value_text(hi) + "], got " + value_text(x));
  }
  template <class V>
  void finite_vector(const std::string& field, const V& v) const {
    for (int i = 0; i < static_cast<int>(v.size()); ++i)
      if (!std::isfinite(static_cast<double>(v[i]))) fail(field, "must be finite, got a non-finite entry at index " + std::to_string(i));
  }
  template <class Q>
  void rotation(const std::string& field, const Q& q) const {
    if (!q.coeffs().allFinite() || q.norm() < real(1e-6)) fail(field, "must be a finite, non-zero quaternion [x, y, z, w]");
  }
  const std::string& where() const { return where_; }
  FieldCheck nested(const std::string& field) const { return FieldCheck(where_ + "." + field); }

 private:
  std::string where_;
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
