// superdex.physics.Error: every error the engine reports, a RuntimeError.

#include <cstring>

#include "bind_common.h"

namespace superdex::python {

void export_error(nb::module_& m) {
  nb::exception<superdex::Error> error_type(m, "Error", PyExc_RuntimeError);
  // Messages quote file contents, which need not be UTF-8 (a malformed file's bytes): decode
  // them with replacement characters instead of failing with a UnicodeDecodeError. Translators
  // registered later are tried first, so this one replaces nanobind's default for Error.
  nb::register_exception_translator(
      [](const std::exception_ptr& p, void* type) {
        try {
          std::rethrow_exception(p);
        } catch (const superdex::Error& e) {
          const char* what = e.what();
          PyObject* message = PyUnicode_DecodeUTF8(what, static_cast<Py_ssize_t>(std::strlen(what)), "replace");
          PyErr_SetObject(static_cast<PyObject*>(type), message);
          Py_XDECREF(message);
        }
      },
      error_type.ptr());

}

}  // namespace superdex::python
