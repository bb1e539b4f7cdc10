// File paths given to the module: a str or any os.PathLike (pathlib.Path), through os.fspath as Python's own
// open() takes them. A path with a NUL byte is refused with ValueError naming it: the C library would cut it
// there and open another file.
#pragma once

#include <string>

#include <pybind11/pybind11.h>

namespace rockfit::python {

struct PathArgument {
  std::string path;
};

}  // namespace rockfit::python

namespace pybind11::detail {

template <>
struct type_caster<rockfit::python::PathArgument> {
  PYBIND11_TYPE_CASTER(rockfit::python::PathArgument, const_name("str | os.PathLike"));

  bool load(handle source, bool /*convert*/) {
    if (!isinstance<str>(source) && !hasattr(source, "__fspath__")) return false;  // TypeError from pybind11
    const object text = module_::import("os").attr("fspath")(source);
    if (!isinstance<str>(text)) return false;  // a bytes path: not supported
    value.path = text.cast<std::string>();
    if (value.path.find('\0') != std::string::npos) {
      throw value_error("path " + repr(text).cast<std::string>() + " contains a NUL byte, which no file name can hold");
    }
    return true;
  }
};

}  // namespace pybind11::detail
