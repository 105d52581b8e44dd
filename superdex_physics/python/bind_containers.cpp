// The DynamicArray and Span types of numbers, strings and value types (the arrays of structs
// are bound next to their struct).

#include <nanobind/stl/string.h>

#include "bind_common.h"
#include "bind_container.h"

namespace superdex::python {

namespace container_detail {

size_t wrap_index(long i, size_t n) {
  if (i < 0) i += static_cast<long>(n);
  if (i < 0 || static_cast<size_t>(i) >= n) throw nb::index_error("index out of range");
  return static_cast<size_t>(i);
}

}  // namespace container_detail

void export_containers(nb::module_& m) {
  bind_dynamic_array<int>(m, "DynamicArrayInt");
  bind_dynamic_array<real>(m, "DynamicArrayReal");
  bind_dynamic_array<bool>(m, "DynamicArrayBool");
  bind_dynamic_array<std::uint8_t>(m, "DynamicArrayUint8");
  bind_dynamic_array<std::string>(m, "DynamicArrayString");
  bind_dynamic_array<Real2>(m, "DynamicArrayReal2");
  bind_dynamic_array<Real3>(m, "DynamicArrayReal3");
  bind_dynamic_array<TransformRT>(m, "DynamicArrayTransformRT");
  bind_dynamic_array<Color>(m, "DynamicArrayColor");

  bind_span<real>(m, "SpanReal");
  bind_span<Real2>(m, "SpanReal2");
  bind_span<TransformRT>(m, "SpanTransformRT");
  bind_span<const int>(m, "SpanConstInt");
  bind_span<const real>(m, "SpanConstReal");
  bind_span<const Real3>(m, "SpanConstReal3");
  bind_span<const std::uint8_t>(m, "SpanConstUint8");
  bind_span<const std::string>(m, "SpanConstString");
  bind_span<const TransformRT>(m, "SpanConstTransformRT");
  bind_span<const Color>(m, "SpanConstColor");
}

}  // namespace superdex::python
