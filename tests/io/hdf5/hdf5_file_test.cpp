#include "rockfit/io/hdf5_file.hpp"

#include <cmath>
#include <fstream>

#include <gtest/gtest.h>
#include <hdf5.h>

#include "python_h5py.hpp"
#include "rockfit/core/errors.hpp"
#include "scratch_dir.hpp"

namespace rockfit::io::hdf5 {
namespace {

using testing::ScratchDir;

TEST(Hdf5File, DatasetsAndAttributesRoundTrip) {
  const ScratchDir dir("hdf5_file");
  const auto path = dir / "a.h5";
  {
    File file = File::Create(path);
    const Group root = file.Root();
    const Group g = root.CreateGroup("trials/T1");  // intermediate group created
    g.WriteDoubles("time_s", {0.0, 0.5, 1.0}, "s");
    g.WriteVectors("w_B_rad_s", {{1, 2, 3}, {4, 5, 6}}, "rad/s");
    g.WriteInts("sample_index", {7, -8}, "1");
    g.WriteStrings("names", {"φ_y", "", "B3-A-1"});
    g.WriteDoubles("empty_s", {}, "s");
    g.SetString("position", "A");
    g.SetDouble("rate_hz", 256.0);
    g.SetInt("count", 42, "time_s");
    root.SetInt("rockfit_schema_version", 1);
    file.Close();
  }
  const File file = File::Open(path);
  const Group g = file.Root().OpenGroup("trials/T1");
  EXPECT_EQ(g.path(), "/trials/T1");
  EXPECT_EQ(g.ReadDoubles("time_s"), (std::vector<double>{0.0, 0.5, 1.0}));
  const auto w = g.ReadVectors("w_B_rad_s");
  ASSERT_EQ(w.size(), 2u);
  EXPECT_EQ(w[1], Eigen::Vector3d(4, 5, 6));
  EXPECT_EQ(g.Shape("w_B_rad_s"), (std::vector<std::size_t>{2, 3}));
  EXPECT_EQ(g.ReadInts("sample_index"), (std::vector<std::int64_t>{7, -8}));
  EXPECT_EQ(g.ReadStrings("names"), (std::vector<std::string>{"φ_y", "", "B3-A-1"}));
  EXPECT_TRUE(g.ReadDoubles("empty_s").empty());
  EXPECT_EQ(g.GetString("units", "time_s"), "s");
  EXPECT_EQ(g.GetString("units", "w_B_rad_s"), "rad/s");
  EXPECT_EQ(g.GetString("position"), "A");
  EXPECT_EQ(g.GetDouble("rate_hz"), 256.0);
  EXPECT_EQ(g.GetInt("count", "time_s"), 42);
  EXPECT_FALSE(g.GetString("missing").has_value());
  EXPECT_EQ(file.Root().OpenGroup("trials").Children(), (std::vector<std::string>{"T1"}));
  EXPECT_TRUE(g.IsDataset("time_s"));
  EXPECT_FALSE(g.IsGroup("time_s"));
  EXPECT_FALSE(file.Root().Exists("fits/T1"));  // missing intermediate component: false, not an HDF5 error
}

TEST(Hdf5File, ReadingMissingOrMisshapedDataIsBadInputNamingFileAndObject) {
  const ScratchDir dir("hdf5_file");
  const auto path = dir / "b.h5";
  {
    File file = File::Create(path);
    file.Root().WriteDoubles("time_s", {1, 2}, "s");
    file.Close();
  }
  const File file = File::Open(path);
  try {
    file.Root().ReadDoubles("nope");
    FAIL();
  } catch (const BadInput& e) {
    EXPECT_NE(std::string(e.what()).find(path.string() + ": no dataset /nope"), std::string::npos) << e.what();
  }
  try {
    file.Root().ReadVectors("time_s");
    FAIL();
  } catch (const BadInput& e) {
    EXPECT_NE(std::string(e.what()).find("/time_s has shape (2), expected (N, 3)"), std::string::npos) << e.what();
  }
  EXPECT_THROW(file.Root().OpenGroup("trials"), BadInput);
}

TEST(Hdf5File, ADatasetClaimingMoreValuesThanItsFileCanHoldIsRefusedBeforeAnyAllocation) {
  // A chunked dataset of 10¹² doubles that was never written: HDF5 stores no chunk, the file stays a few kB,
  // and reading it would allocate 8 TB. rockfit reads at most 4096 × the file's size.
  const ScratchDir dir("hdf5_file");
  const auto path = dir / "huge.h5";
  {
    const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    const hsize_t dims[1] = {1000000000000ULL};
    const hsize_t chunk[1] = {1024};
    const hid_t space = H5Screate_simple(1, dims, nullptr);
    const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_chunk(dcpl, 1, chunk);
    const hid_t dataset = H5Dcreate2(file, "time_s", H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    ASSERT_GE(dataset, 0);
    H5Dclose(dataset);
    H5Pclose(dcpl);
    H5Sclose(space);
    H5Fclose(file);
  }
  const File file = File::Open(path);
  try {
    file.Root().ReadDoubles("time_s");
    FAIL();
  } catch (const BadInput& e) {
    EXPECT_NE(std::string(e.what()).find("dataset /time_s claims a shape of 1000000000000 values in a file of"),
              std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("write it again with rockfit or restore a copy"), std::string::npos);
  }
  EXPECT_THROW(file.Root().ReadStrings("time_s"), BadInput);
}

TEST(Hdf5File, OpeningSomethingElseIsBadInput) {
  const ScratchDir dir("hdf5_file");
  std::ofstream(dir / "text.h5") << "not hdf5\n";
  EXPECT_THROW(File::Open(dir / "text.h5"), BadInput);
  EXPECT_THROW(File::Open(dir / "missing.h5"), BadInput);
  EXPECT_FALSE(File::IsHdf5(dir / "text.h5"));
}

TEST(Hdf5File, WritingOverAnExistingObjectIsAnOutputError) {
  const ScratchDir dir("hdf5_file");
  File file = File::Create(dir / "c.h5");
  file.Root().WriteDoubles("x", {1}, "1");
  EXPECT_THROW(file.Root().WriteDoubles("x", {2}, "1"), OutputError);
  EXPECT_THROW(file.Root().CreateGroup("x"), OutputError);
  file.Root().Remove("x");
  EXPECT_FALSE(file.Root().Exists("x"));
}

TEST(Hdf5File, AttributesAndObjectsCopyBetweenFiles) {
  const ScratchDir dir("hdf5_file");
  File a = File::Create(dir / "a.h5");
  const Group g = a.Root().CreateGroup("fits/T1");
  g.SetString("note", "kept");
  g.SetDouble("epsilon_rad_s", 0.01);
  g.WriteStrings("names", {"a", "b"});
  a.Root().SetString("who", "fit");
  File b = File::Create(dir / "b.h5");
  CopyObject(a.Root(), "fits", b.Root());
  CopyAttributes(a.Root(), b.Root());
  EXPECT_EQ(b.Root().OpenGroup("fits/T1").GetString("note"), "kept");
  EXPECT_EQ(b.Root().OpenGroup("fits/T1").ReadStrings("names"), (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(b.Root().GetString("who"), "fit");
}

TEST(Hdf5File, H5pyReadsNamesShapesUnitsAndStrings) {
  ROCKFIT_REQUIRE_H5PY();
  const ScratchDir dir("hdf5_file");
  const auto path = dir / "d.h5";
  {
    File file = File::Create(path);
    const Group g = file.Root().CreateGroup("trials/T1");
    g.WriteVectors("w_B_rad_s", {{1, 2, 3}, {4, 5, 6}, {7, 8, 9}}, "rad/s");
    g.WriteStrings("names", {"a", "φ"});
    g.SetString("position", "B");
    file.Close();
  }
  const auto result = testing::RunH5pyScript(R"(
import sys, h5py
f = h5py.File(sys.argv[1], 'r')
w = f['trials/T1/w_B_rad_s']
assert w.shape == (3, 3), w.shape
assert w.dtype == 'float64'
assert w.attrs['units'] == 'rad/s', w.attrs['units']
assert w[1, 2] == 6.0
assert list(f['trials/T1/names'].asstr()[...]) == ['a', 'φ']
assert f['trials/T1'].attrs['position'] == 'B'
print('ok')
)", path);
  EXPECT_EQ(result.exit_code, 0) << result.out;
  EXPECT_EQ(result.out, "ok\n");
}

}  // namespace
}  // namespace rockfit::io::hdf5
