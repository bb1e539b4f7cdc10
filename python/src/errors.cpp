// rockfit's errors as Python exceptions, with the library's messages unchanged:
//   InvalidArgument  → ValueError
//   BadInput         → rockfit.InputError (a ValueError) with .path, .line, .column parsed from the message
//   NumericalFailure → rockfit.NumericalError (a RuntimeError)
//   OutputError      → rockfit.OutputError (an OSError)
#include "bindings.hpp"
#include "rockfit/core/errors.hpp"

namespace rockfit::python {
namespace {

constexpr const char* kErrorsSource = R"PY(
import re as _re

_POSITION = _re.compile(r"^(?P<path>[^\n]+?):(?P<line>\d+)(?::(?P<column>\d+))?: ")
_FILE = _re.compile(r"^(?P<path>[^\s:'\"][^\n:]*?\.[A-Za-z0-9]+|[^\s:'\"][^\n:]*/[^\n:]*?): ")


class InputError(ValueError):
    """A file or manifest that rockfit cannot use as it is (the program's exit code 2).

    The message names the file, line and column where known, what was found and what to do.
    Attributes: path (str or None), line and column (1-based int, or None when not known).
    """

    def __init__(self, message):
        super().__init__(message)
        self.path = None
        self.line = None
        self.column = None
        match = _POSITION.match(message)
        if match:
            self.path = match["path"]
            self.line = int(match["line"])
            self.column = int(match["column"]) if match["column"] else None
            return
        match = _FILE.match(message)
        if match:
            self.path = match["path"]


class NumericalError(RuntimeError):
    """A computation that could not produce a meaningful result (the program's exit code 3)."""


class OutputError(OSError):
    """An output file that could not be written (the program's exit code 4); existing files are untouched."""
)PY";

py::object* g_input_error = nullptr;
py::object* g_numerical_error = nullptr;
py::object* g_output_error = nullptr;

void SetError(const py::object* type, const char* message) { PyErr_SetObject(type->ptr(), py::str(message).ptr()); }

}  // namespace

void RegisterErrors(py::module_& m) {
  py::dict scope;
  scope["__name__"] = m.attr("__name__");
  scope["__builtins__"] = py::module_::import("builtins");
  py::exec(kErrorsSource, scope);
  for (const char* name : {"InputError", "NumericalError", "OutputError"}) {
    scope[name].attr("__module__") = m.attr("__name__");
    m.attr(name) = scope[name];
  }
  // Leaked on purpose: the translator may run until the interpreter shuts down.
  g_input_error = new py::object(scope["InputError"]);
  g_numerical_error = new py::object(scope["NumericalError"]);
  g_output_error = new py::object(scope["OutputError"]);
  py::register_exception_translator([](std::exception_ptr p) {
    if (!p) return;
    try {
      std::rethrow_exception(p);
    } catch (const BadInput& e) {
      SetError(g_input_error, e.what());
    } catch (const NumericalFailure& e) {
      SetError(g_numerical_error, e.what());
    } catch (const OutputError& e) {
      SetError(g_output_error, e.what());
    } catch (const InvalidArgument& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
}

}  // namespace rockfit::python
