// The HDF5 trajectory file: layout, units attributes, schema version, and the atomic write.
#include "rockfit/io/trajectory_hdf5.hpp"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <hdf5.h>
#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"
#include "simulation_cases.hpp"

namespace rockfit::io {
namespace {

struct TempDir {
  std::filesystem::path path;
  TempDir() {
    path = std::filesystem::temp_directory_path() / ("rockfit_traj_h5_" + std::to_string(::getpid()));
    std::filesystem::create_directories(path);
  }
  ~TempDir() { std::filesystem::remove_all(path); }
};

struct SimulatedRun {
  core::Block block = testing::Fig14Block();
  core::ModelParameters params = testing::Fig14Parameters();
  core::SimulationOptions options;
  core::Trajectory trajectory;
  SimulatedRun() { trajectory = core::Simulate(block, params, options); }
};

std::vector<double> ReadDoubles(hid_t file, const char* name, std::vector<hsize_t>* dims) {
  const hid_t dataset = H5Dopen2(file, name, H5P_DEFAULT);
  EXPECT_GE(dataset, 0) << name;
  const hid_t space = H5Dget_space(dataset);
  const int rank = H5Sget_simple_extent_ndims(space);
  dims->assign(rank, 0);
  H5Sget_simple_extent_dims(space, dims->data(), nullptr);
  std::size_t n = 1;
  for (hsize_t d : *dims) n *= d;
  std::vector<double> data(n);
  if (n > 0) H5Dread(dataset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data());
  H5Sclose(space);
  H5Dclose(dataset);
  return data;
}

std::string ReadStringAttribute(hid_t object, const char* name) {
  const hid_t attribute = H5Aopen(object, name, H5P_DEFAULT);
  EXPECT_GE(attribute, 0) << name;
  const hid_t type = H5Aget_type(attribute);
  char* text = nullptr;
  H5Aread(attribute, type, &text);
  std::string value = text != nullptr ? text : "";
  H5free_memory(text);
  H5Tclose(type);
  H5Aclose(attribute);
  return value;
}

TEST(TrajectoryHdf5, WritesSamplesImpactsAndUnitsThatReadBack) {
  const SimulatedRun run;
  const TempDir dir;
  const std::filesystem::path path = dir.path / "fig14.h5";
  WriteTrajectoryHdf5(path, run.block, run.params, run.options, run.trajectory);
  // Only the finished file is left in the directory.
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path), std::filesystem::directory_iterator()), 1);

  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  EXPECT_EQ(ReadStringAttribute(file, "schema"), kTrajectorySchemaName);
  long long version = 0;
  const hid_t version_attribute = H5Aopen(file, "rockfit_schema_version", H5P_DEFAULT);
  H5Aread(version_attribute, H5T_NATIVE_LLONG, &version);
  H5Aclose(version_attribute);
  EXPECT_EQ(version, kTrajectorySchemaVersion);

  std::vector<hsize_t> dims;
  const std::vector<double> t = ReadDoubles(file, "/samples/time_s", &dims);
  ASSERT_EQ(dims, std::vector<hsize_t>{static_cast<hsize_t>(run.trajectory.t_s.size())});
  EXPECT_EQ(t, run.trajectory.t_s);
  const std::vector<double> w = ReadDoubles(file, "/samples/w_B_rad_s", &dims);
  ASSERT_EQ(dims, (std::vector<hsize_t>{static_cast<hsize_t>(run.trajectory.t_s.size()), 3}));
  EXPECT_EQ(w[3 * 10 + 1], run.trajectory.w_B[10].y());
  const std::vector<double> q = ReadDoubles(file, "/samples/q_WB", &dims);
  ASSERT_EQ(dims, (std::vector<hsize_t>{static_cast<hsize_t>(run.trajectory.t_s.size()), 4}));
  EXPECT_EQ(q[4 * 10], run.trajectory.q_WB[10].w());  // scalar first
  const std::vector<double> impact_t = ReadDoubles(file, "/impacts/t_s", &dims);
  ASSERT_EQ(dims, std::vector<hsize_t>{static_cast<hsize_t>(run.trajectory.impacts.size())});
  EXPECT_EQ(impact_t.back(), run.trajectory.impacts.back().t_s);

  const hid_t w_dataset = H5Dopen2(file, "/samples/w_B_rad_s", H5P_DEFAULT);
  EXPECT_EQ(ReadStringAttribute(w_dataset, "units"), "rad/s");
  H5Dclose(w_dataset);
  const hid_t energy_dataset = H5Dopen2(file, "/impacts/delta_energy_J", H5P_DEFAULT);
  EXPECT_EQ(ReadStringAttribute(energy_dataset, "units"), "J");
  H5Dclose(energy_dataset);
  const hid_t result = H5Gopen2(file, "/result", H5P_DEFAULT);
  EXPECT_EQ(ReadStringAttribute(result, "end_reason"), "phase4");
  H5Gclose(result);
  H5Fclose(file);
}

TEST(TrajectoryHdf5, AFailedWriteLeavesNothingBehindAndDamagesNothing) {
  const SimulatedRun run;
  const TempDir dir;
  // The directory does not exist.
  EXPECT_THROW(WriteTrajectoryHdf5(dir.path / "missing-subdir" / "out.h5", run.block, run.params, run.options,
                                   run.trajectory),
               OutputError);
  // The target is an existing, non-empty directory: the file is written to a temporary name, the final rename
  // fails, the temporary is removed and the directory keeps its content.
  const std::filesystem::path target = dir.path / "taken.h5";
  std::filesystem::create_directories(target);
  { std::ofstream(target / "keep.txt") << "keep"; }
  EXPECT_THROW(WriteTrajectoryHdf5(target, run.block, run.params, run.options, run.trajectory), OutputError);
  EXPECT_TRUE(std::filesystem::is_regular_file(target / "keep.txt"));
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path), std::filesystem::directory_iterator()), 1);
}

}  // namespace
}  // namespace rockfit::io
