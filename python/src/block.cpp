// rockfit.Block: the homogeneous cuboid 2b1 × 2b2 × 2h (core/block.hpp), immutable.
#include <fmt/format.h>

#include "bindings.hpp"
#include "path_argument.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/io/manifest.hpp"

namespace rockfit::python {

void RegisterBlock(py::module_& m) {
  py::class_<core::Block>(m, "Block",
                          "A rigid homogeneous block 2·b1 × 2·b2 × 2·h, immutable.\n\n"
                          "Block(b1, b2, h, density=None, mass=None): half-sizes b1 (along x), b2 (along y) and h (the\n"
                          "COM height = half the block height) in m, with exactly one of density [kg/m³] or mass [kg].\n"
                          "Block.from_manifest(path, id) takes a block of a campaign manifest (TOML).")
      .def(py::init([](double b1, double b2, double h, std::optional<double> density, std::optional<double> mass) {
             if (density.has_value() == mass.has_value()) {
               throw InvalidArgument("give exactly one of density= (kg/m³) or mass= (kg) for the block");
             }
             return density ? core::Block::FromDensity(b1, b2, h, *density) : core::Block::FromMass(b1, b2, h, *mass);
           }),
           py::arg("b1"), py::arg("b2"), py::arg("h"), py::kw_only(), py::arg("density") = py::none(),
           py::arg("mass") = py::none())
      .def_static(
          "from_manifest",
          [](const PathArgument& path, const std::string& id) {
            return io::ReadManifest(path.path).FindBlock(id).ToBlock();
          },
          py::arg("path"), py::arg("id"),
          "The block `id` of the campaign manifest at `path` (TOML). Raises rockfit.InputError naming the file, line\n"
          "and column for a bad manifest or an unknown id.")
      .def_property_readonly("b1", &core::Block::b1, "Half-width along x [m]")
      .def_property_readonly("b2", &core::Block::b2, "Half-depth along y [m]")
      .def_property_readonly("h", &core::Block::h, "Height of the COM above the base (half the block height) [m]")
      .def_property_readonly("mass", &core::Block::mass, "Mass [kg]")
      .def_property_readonly("density", &core::Block::density, "Density [kg/m³]")
      .def_property_readonly(
          "inertia_C_B",
          [](const core::Block& b) {
            py::array_t<double> out({3, 3});
            auto v = out.mutable_unchecked<2>();
            for (py::ssize_t i = 0; i < 3; ++i)
              for (py::ssize_t j = 0; j < 3; ++j) v(i, j) = b.inertia_C_B()(i, j);
            return out;
          },
          "Inertia tensor about the COM in B [kg·m²]: m/3·diag(b2²+h², b1²+h², b1²+b2²), a (3, 3) array")
      .def_property_readonly("p_BC_B", [](const core::Block& b) { return Vector3Array(b.p_BC_B()); },
                             "Position of the COM in B [m]: (0, 0, h)")
      .def(
          "vertex", [](const core::Block& b, int k) { return Vector3Array(b.p_BV_B(k)); }, py::arg("k"),
          "Position of base vertex V_k in B [m]; k is taken cyclically (0 is V4, 5 is V1)")
      .def("__repr__",
           [](const core::Block& b) {
             return fmt::format("Block(b1={:.9g}, b2={:.9g}, h={:.9g}, mass={:.9g})", b.b1(), b.b2(), b.h(), b.mass());
           })
      .def(py::pickle(
          [](const core::Block& b) { return py::make_tuple(b.b1(), b.b2(), b.h(), b.mass()); },
          [](const py::tuple& t) {
            return core::Block::FromMass(t[0].cast<double>(), t[1].cast<double>(), t[2].cast<double>(),
                                         t[3].cast<double>());
          }));
}

}  // namespace rockfit::python
