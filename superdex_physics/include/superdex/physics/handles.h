#pragma once
/// @file handles.h
/// Handles: every scene, shape, actor, captured state, query and callback gets a distinct positive
/// id drawn from one engine-wide counter; ids are never reused, so a stale handle is always
/// detected. 0 is the invalid handle. Each kind has its own type (SceneHandle, ActorHandle, ...);
/// they convert to and from the raw 64-bit id for storage and printing.
///
/// ShapeHandle counts references: a copy adds one, destruction drops one, and the shape is
/// released when the last reference goes (or at once by release_shape()). Actors keep the data of
/// the shape they were made from, so a shape may be released as soon as its actors exist.

#include <compare>
#include <cstdint>
#include <functional>

#include "superdex/physics/real.h"

namespace superdex::physics {

/// A typed 64-bit id; 0 is invalid.
template <class Tag>
struct Handle {
  std::int64_t value = 0;
  constexpr Handle() = default;
  constexpr Handle(std::int64_t raw) : value(raw) {}  // NOLINT: ids flow in from the engine's counter
  constexpr operator std::int64_t() const { return value; }  // NOLINT: maps and messages use the raw id
  constexpr bool is_valid() const { return value != 0; }
};

/// JSON form of a handle (nlohmann::json finds it by argument-dependent lookup): the raw id.
template <class Json, class Tag>
void to_json(Json& j, const Handle<Tag>& h) {
  j = h.value;
}
template <class Json, class Tag>
void from_json(const Json& j, Handle<Tag>& h) {
  h.value = j.template get<std::int64_t>();
}

struct SceneTag;
struct ActorTag;
struct StateTag;
struct QueryTag;
struct CallbackTag;
struct ConstraintTag;
using SceneHandle = Handle<SceneTag>;
using ActorHandle = Handle<ActorTag>;
/// A captured scene state (Scene::capture_state).
using StateHandle = Handle<StateTag>;
/// A registered query of an actor (Scene::register_query).
using QueryHandle = Handle<QueryTag>;
/// A registered step callback (Scene::register_pre_step_callback).
using CallbackHandle = Handle<CallbackTag>;
using ConstraintHandle = Handle<ConstraintTag>;

/// The next unused id (thread-safe; shared by both precisions' builds).
std::int64_t next_handle();

inline namespace SUPERDEX_REAL_NAMESPACE {

/// A counted reference to a registered shape (see the file comment).
class ShapeHandle {
 public:
  ShapeHandle() = default;
  /// A new reference to the shape with id `value` (a reference to nothing if no such shape lives).
  explicit ShapeHandle(std::int64_t value);
  ShapeHandle(const ShapeHandle& other);
  ShapeHandle(ShapeHandle&& other) noexcept : value_(other.value_) { other.value_ = 0; }
  ShapeHandle& operator=(const ShapeHandle& other);
  ShapeHandle& operator=(ShapeHandle&& other) noexcept;
  ~ShapeHandle();

  /// Takes over the reference a shape is created with (the registry's use).
  static ShapeHandle adopt(std::int64_t value) {
    ShapeHandle h;
    h.value_ = value;
    return h;
  }
  std::int64_t value() const { return value_; }
  /// Points this handle at another shape id (dropping its reference, taking one on the new one).
  void set_value(std::int64_t value);
  bool is_valid() const { return value_ != 0; }
  friend bool operator==(const ShapeHandle& a, const ShapeHandle& b) { return a.value_ == b.value_; }
  friend auto operator<=>(const ShapeHandle& a, const ShapeHandle& b) { return a.value_ <=> b.value_; }

 private:
  std::int64_t value_ = 0;
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

template <class Tag>
struct std::hash<superdex::physics::Handle<Tag>> {
  size_t operator()(const superdex::physics::Handle<Tag>& h) const noexcept { return std::hash<std::int64_t>()(h.value); }
};
template <>
struct std::hash<superdex::physics::ShapeHandle> {
  size_t operator()(const superdex::physics::ShapeHandle& h) const noexcept { return std::hash<std::int64_t>()(h.value()); }
};
