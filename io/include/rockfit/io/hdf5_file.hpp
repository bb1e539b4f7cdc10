// A small RAII layer over the HDF5 C API for rockfit's files (docs/design.md §8): files, groups, float64/int64/string
// datasets of one or two dimensions with a `units` attribute, and scalar attributes. It hides <hdf5.h> so that
// every library can use it; all failures are exceptions whose message names the file and the object:
// BadInput when reading, OutputError when writing. Atomic rewrites are in hdf5_transaction.hpp.
//
// Conventions of rockfit's files: units are part of the dataset name (`time_s`, `w_B_rad_s`) and repeated in
// the `units` attribute ("1" for dimensionless values); N×3 arrays are stored row-major, shape (N, 3) in
// h5py/NumPy (MATLAB's h5read shows them transposed, 3×N); strings are variable-length UTF-8.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace rockfit::io::hdf5 {

// An HDF5 identifier (hid_t) and the function that closes it; move-only.
class Handle {
 public:
  using Id = std::int64_t;
  using Closer = int (*)(Id);
  Handle() = default;
  Handle(Id id, Closer closer) : id_(id), closer_(closer) {}
  Handle(Handle&& other) noexcept : id_(other.id_), closer_(other.closer_) { other.id_ = -1; }
  Handle& operator=(Handle&& other) noexcept;
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() { Reset(); }
  Id id() const { return id_; }
  bool valid() const { return id_ >= 0; }
  void Reset();
  // Gives up ownership: returns the id, which the caller must close.
  Id Release() {
    const Id id = id_;
    id_ = -1;
    return id;
  }

 private:
  Id id_ = -1;
  Closer closer_ = nullptr;
};

// A group (or the root group of a file).
class Group {
 public:
  // Children: groups. Names may contain '/' (a path below this group).
  bool Exists(const std::string& name) const;     // a link of that name exists (every component checked)
  bool IsGroup(const std::string& name) const;
  bool IsDataset(const std::string& name) const;
  Group OpenGroup(const std::string& name) const;     // BadInput when missing
  Group CreateGroup(const std::string& name) const;   // creates missing intermediate groups; OutputError if it exists
  Group OpenOrCreateGroup(const std::string& name) const;  // open, or create when missing
  void Remove(const std::string& name) const;              // unlinks; nothing when missing
  std::vector<std::string> Children() const;               // names of the direct children, in name order

  // Datasets.
  void WriteDoubles(const std::string& name, const std::vector<double>& values, const std::string& units) const;
  // rows × columns, row-major.
  void WriteMatrix(const std::string& name, const std::vector<double>& row_major, std::size_t rows, std::size_t columns,
                   const std::string& units) const;
  void WriteVectors(const std::string& name, const std::vector<Eigen::Vector3d>& rows, const std::string& units) const;
  void WriteInts(const std::string& name, const std::vector<std::int64_t>& values, const std::string& units) const;
  void WriteStrings(const std::string& name, const std::vector<std::string>& values) const;

  std::vector<std::size_t> Shape(const std::string& name) const;
  // Any numeric dataset, converted to double; `shape` receives the dimensions.
  std::vector<double> ReadDoubles(const std::string& name, std::vector<std::size_t>* shape = nullptr) const;
  // An (N, 3) dataset; BadInput for another shape.
  std::vector<Eigen::Vector3d> ReadVectors(const std::string& name) const;
  std::vector<std::int64_t> ReadInts(const std::string& name) const;
  std::vector<std::string> ReadStrings(const std::string& name) const;

  // Scalar attributes of this group (object empty) or of a child object.
  void SetString(const std::string& attribute, const std::string& value, const std::string& object = "") const;
  void SetDouble(const std::string& attribute, double value, const std::string& object = "") const;
  void SetInt(const std::string& attribute, std::int64_t value, const std::string& object = "") const;
  bool HasAttribute(const std::string& attribute, const std::string& object = "") const;
  std::optional<std::string> GetString(const std::string& attribute, const std::string& object = "") const;
  std::optional<double> GetDouble(const std::string& attribute, const std::string& object = "") const;
  std::optional<std::int64_t> GetInt(const std::string& attribute, const std::string& object = "") const;

  // "/trials/T1" and the file's name, for messages.
  const std::string& path() const { return path_; }
  const std::string& file_name() const { return file_name_; }
  Handle::Id id() const { return handle_.id(); }

 private:
  friend class File;
  Group(Handle handle, std::string path, std::string file_name)
      : handle_(std::move(handle)), path_(std::move(path)), file_name_(std::move(file_name)) {}
  std::string ChildPath(const std::string& name) const;
  Handle OpenObject(const std::string& object) const;

  Handle handle_;
  std::string path_;
  std::string file_name_;
};

class File {
 public:
  // Creates (truncates) a file. OutputError when it cannot.
  static File Create(const std::filesystem::path& path);
  // Creates a file held in memory only (HDF5's core driver, no backing store); `name` identifies it in messages.
  // Image() gives its bytes. Writers build their output this way and write it to disk in one go
  // (hdf5_transaction.hpp), so a full disk is an error of rockfit's own write, never one inside libhdf5 (whose
  // error paths crash on EFBIG, HDF5 1.10).
  static File CreateInMemory(const std::filesystem::path& name);
  // Opens an existing file. BadInput when it is missing or not HDF5.
  static File Open(const std::filesystem::path& path, bool writable = false);
  // True when `path` is a readable HDF5 file.
  static bool IsHdf5(const std::filesystem::path& path);

  Group Root() const;
  const std::filesystem::path& path() const { return path_; }
  Handle::Id id() const { return handle_.id(); }
  void Flush() const;
  // The bytes of the whole file (flushed first). OutputError when HDF5 cannot give them.
  std::string Image() const;
  // Closes the file and every object still open in it. OutputError when buffered data cannot be written.
  void Close();

 private:
  File(Handle handle, std::filesystem::path path) : handle_(std::move(handle)), path_(std::move(path)) {}
  Handle handle_;
  std::filesystem::path path_;
};

// Copies `name` (a dataset or a whole group with its attributes) from one group to another.
void CopyObject(const Group& from, const std::string& name, const Group& to);
// Copies every attribute of `from` (its own, not its children's) onto `to`, replacing those of the same name.
void CopyAttributes(const Group& from, const Group& to);

}  // namespace rockfit::io::hdf5
