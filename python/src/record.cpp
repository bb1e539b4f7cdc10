// numpy conversions and the Record type of results (bindings.hpp).
#include <cstring>
#include <memory>

#include <fmt/format.h>

#include "bindings.hpp"

namespace rockfit::python {
namespace {

// The Record class, written in Python so that help(), dir() and repr() behave as Python users expect.
constexpr const char* kRecordSource = R"PY(
class Record:
    """A rockfit result: named fields readable as attributes and as a mapping.

    r.epsilon, r["epsilon"], "epsilon" in r, r.keys(), r.items(), r.get(name, default), r.to_dict(),
    r.type_name.
    The fields of each result are listed in the docstring of the function that returns it; arrays are
    numpy arrays in SI units (s, rad, rad/s, m, kg, J, N*m*s). Records are read-only.
    """

    __slots__ = ("_type", "_fields")

    def __init__(self, type_name, fields):
        object.__setattr__(self, "_type", type_name)
        object.__setattr__(self, "_fields", dict(fields))

    def __getattr__(self, name):
        try:
            return self._fields[name]
        except KeyError:
            raise AttributeError(
                f"{self._type} has no field '{name}'; its fields are: {', '.join(self._fields)}") from None

    def __setattr__(self, name, value):
        raise AttributeError(f"{self._type} is read-only; copy it with to_dict() to change values")

    def __getitem__(self, key):
        return self._fields[key]

    def __contains__(self, key):
        return key in self._fields

    def __iter__(self):
        return iter(self._fields)

    def __len__(self):
        return len(self._fields)

    def __dir__(self):
        return sorted(set(self._fields) | {"keys", "items", "get", "to_dict", "type_name"})

    def __eq__(self, other):
        return NotImplemented

    __hash__ = None

    def keys(self):
        return self._fields.keys()

    def items(self):
        return self._fields.items()

    def get(self, key, default=None):
        return self._fields.get(key, default)

    @property
    def type_name(self):
        return self._type

    def to_dict(self):
        """The fields as plain dicts and lists (nested records converted too; arrays stay numpy arrays)."""
        def plain(v):
            if isinstance(v, Record):
                return v.to_dict()
            if isinstance(v, dict):
                return {k: plain(x) for k, x in v.items()}
            if isinstance(v, list):
                return [plain(x) for x in v]
            return v
        return {k: plain(v) for k, v in self._fields.items()}

    @staticmethod
    def _short(v, depth=0):
        if isinstance(v, Record):
            return repr(v) if depth < 1 else f"{v._type}(…)"
        if hasattr(v, "shape") and hasattr(v, "dtype"):
            if v.ndim == 1 and v.size <= 4:
                return "array([" + ", ".join(f"{x:.6g}" for x in v.tolist()) + "])"
            return f"array{tuple(v.shape)}"
        if isinstance(v, float):
            return f"{v:.6g}"
        if isinstance(v, dict):
            if len(v) > 8 or depth > 1:
                return "{" + f"{len(v)} keys" + "}"
            return "{" + ", ".join(f"{k!r}: {Record._short(x, depth + 1)}" for k, x in v.items()) + "}"
        if isinstance(v, list):
            if len(v) > 4 or depth > 1 or any(isinstance(x, (Record, dict, list)) for x in v):
                return f"[{len(v)} items]"
            return "[" + ", ".join(Record._short(x, depth + 1) for x in v) + "]"
        text = repr(v)
        return text if len(text) <= 80 else text[:77] + "…'"

    def __repr__(self):
        return f"{self._type}(" + ", ".join(f"{k}={Record._short(v)}" for k, v in self._fields.items()) + ")"
)PY";

py::object* g_record_class = nullptr;

template <typename Container>
py::capsule OwnerOf(Container* heap) {
  return py::capsule(heap, [](void* p) { delete static_cast<Container*>(p); });
}

}  // namespace

void RegisterRecord(py::module_& m) {
  py::dict scope;
  scope["__name__"] = m.attr("__name__");
  scope["__builtins__"] = py::module_::import("builtins");
  py::exec(kRecordSource, scope);
  py::object cls = scope["Record"];
  cls.attr("__module__") = m.attr("__name__");
  m.attr("Record") = cls;
  g_record_class = new py::object(cls);  // leaked on purpose: outlives every result
}

py::object MakeRecord(const std::string& type_name, py::dict fields) {
  if (g_record_class == nullptr) throw std::logic_error("rockfit.Record used before the module was initialised");
  return (*g_record_class)(type_name, fields);
}

py::array_t<double> OwnedArray(std::vector<double>&& values) {
  auto* heap = new std::vector<double>(std::move(values));
  return py::array_t<double>({static_cast<py::ssize_t>(heap->size())}, {static_cast<py::ssize_t>(sizeof(double))},
                             heap->data(), OwnerOf(heap));
}

py::array_t<double> OwnedArray(std::vector<Eigen::Vector3d>&& vectors) {
  static_assert(sizeof(Eigen::Vector3d) == 3 * sizeof(double), "Vector3d must be three packed doubles");
  auto* heap = new std::vector<Eigen::Vector3d>(std::move(vectors));
  const py::ssize_t n = static_cast<py::ssize_t>(heap->size());
  return py::array_t<double>({n, py::ssize_t{3}},
                             {static_cast<py::ssize_t>(sizeof(Eigen::Vector3d)), static_cast<py::ssize_t>(sizeof(double))},
                             heap->empty() ? nullptr : heap->front().data(), OwnerOf(heap));
}

py::array_t<double> QuaternionArray(const std::vector<Eigen::Quaterniond>& quaternions) {
  py::array_t<double> out({static_cast<py::ssize_t>(quaternions.size()), py::ssize_t{4}});
  auto view = out.mutable_unchecked<2>();
  for (std::size_t k = 0; k < quaternions.size(); ++k) {
    const auto i = static_cast<py::ssize_t>(k);
    view(i, 0) = quaternions[k].w();
    view(i, 1) = quaternions[k].x();
    view(i, 2) = quaternions[k].y();
    view(i, 3) = quaternions[k].z();
  }
  return out;
}

py::array_t<double> Vector3Array(const Eigen::Vector3d& v) {
  py::array_t<double> out(3);
  std::memcpy(out.mutable_data(), v.data(), 3 * sizeof(double));
  return out;
}

py::array_t<double> ViewArray(std::vector<double>& values, py::handle owner) {
  return py::array_t<double>({static_cast<py::ssize_t>(values.size())}, {static_cast<py::ssize_t>(sizeof(double))},
                             values.data(), owner);
}

py::array_t<double> ViewArray(std::vector<Eigen::Vector3d>& vectors, py::handle owner) {
  const py::ssize_t n = static_cast<py::ssize_t>(vectors.size());
  return py::array_t<double>({n, py::ssize_t{3}},
                             {static_cast<py::ssize_t>(sizeof(Eigen::Vector3d)), static_cast<py::ssize_t>(sizeof(double))},
                             vectors.empty() ? nullptr : vectors.front().data(), owner);
}

namespace {

py::array_t<double, py::array::c_style | py::array::forcecast> AsFloatArray(const py::handle& value, const char* name) {
  if (value.is_none()) throw py::value_error(fmt::format("{} must be an array of numbers, got None", name));
  try {
    return py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
  } catch (const py::error_already_set&) {
  }
  throw py::value_error(fmt::format("{} must be an array of numbers", name));
}

}  // namespace

Eigen::Vector3d ToVector3(const py::handle& value, const char* name) {
  const auto a = AsFloatArray(value, name);
  if (!a || a.ndim() != 1 || a.shape(0) != 3) {
    throw py::value_error(fmt::format("{} must be a vector of 3 numbers (x, y, z)", name));
  }
  return Eigen::Vector3d(a.at(0), a.at(1), a.at(2));
}

std::vector<double> ToDoubles(const py::handle& value, const char* name) {
  const auto a = AsFloatArray(value, name);
  if (!a || a.ndim() != 1) throw py::value_error(fmt::format("{} must be a 1-D array of numbers", name));
  return std::vector<double>(a.data(), a.data() + a.shape(0));
}

std::vector<Eigen::Vector3d> ToVectors3(const py::handle& value, const char* name) {
  const auto a = AsFloatArray(value, name);
  if (!a || a.ndim() != 2 || a.shape(1) != 3) {
    throw py::value_error(fmt::format("{} must be an (N, 3) array of numbers", name));
  }
  std::vector<Eigen::Vector3d> out(static_cast<std::size_t>(a.shape(0)));
  if (!out.empty()) std::memcpy(out.front().data(), a.data(), out.size() * 3 * sizeof(double));
  return out;
}

py::object FromJson(const nlohmann::json& value) {
  switch (value.type()) {
    case nlohmann::json::value_t::null:
      return py::none();
    case nlohmann::json::value_t::boolean:
      return py::bool_(value.get<bool>());
    case nlohmann::json::value_t::number_integer:
      return py::int_(value.get<std::int64_t>());
    case nlohmann::json::value_t::number_unsigned:
      return py::int_(value.get<std::uint64_t>());
    case nlohmann::json::value_t::number_float:
      return py::float_(value.get<double>());
    case nlohmann::json::value_t::string:
      return py::str(value.get_ref<const std::string&>());
    case nlohmann::json::value_t::array: {
      py::list out;
      for (const auto& item : value) out.append(FromJson(item));
      return std::move(out);
    }
    case nlohmann::json::value_t::object: {
      py::dict out;
      for (const auto& [key, item] : value.items()) out[py::str(key)] = FromJson(item);
      return std::move(out);
    }
    default:
      return py::none();
  }
}

py::dict BlockDict(const core::Block& block) {
  py::dict d;
  d["b1"] = block.b1();
  d["b2"] = block.b2();
  d["h"] = block.h();
  d["mass"] = block.mass();
  return d;
}

}  // namespace rockfit::python
