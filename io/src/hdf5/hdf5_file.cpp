#include "rockfit/io/hdf5_file.hpp"

#include <hdf5.h>
#include <sys/stat.h>

#include <cstring>
#include <type_traits>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"
#include "text/text_file.hpp"

namespace rockfit::io::hdf5 {

static_assert(std::is_same_v<hid_t, Handle::Id>, "Handle::Id must be hid_t");

namespace {

// HDF5 prints its error stack on stderr by default; rockfit reports errors itself.
void SilenceHdf5() {
  static const bool silenced = [] {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    return true;
  }();
  (void)silenced;
}

// The innermost message of the current HDF5 error stack ("" when there is none).
std::string Hdf5Reason() {
  std::string reason;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_UPWARD,
      [](unsigned, const H5E_error2_t* error, void* data) -> herr_t {
        auto* out = static_cast<std::string*>(data);
        if (out->empty() && error->desc) *out = error->desc;
        return 0;
      },
      &reason);
  H5Eclear2(H5E_DEFAULT);
  return reason.empty() ? std::string() : " (HDF5: " + reason + ")";
}

[[noreturn]] void ThrowUnreadable(const std::string& file, const std::string& what) {
  throw BadInput(fmt::format("{}: {}{}", file, what, Hdf5Reason()));
}
[[noreturn]] void ThrowOutputError(const std::string& file, const std::string& what) {
  throw OutputError(fmt::format("{}: {}{}; check free space and permissions", file, what, Hdf5Reason()));
}

int CloseGroup(hid_t id) { return H5Gclose(id); }
int CloseDataset(hid_t id) { return H5Dclose(id); }
int CloseSpace(hid_t id) { return H5Sclose(id); }
int CloseType(hid_t id) { return H5Tclose(id); }
int CloseAttribute(hid_t id) { return H5Aclose(id); }
int CloseObject(hid_t id) { return H5Oclose(id); }
int ClosePlist(hid_t id) { return H5Pclose(id); }
int CloseFile(hid_t id) { return H5Fclose(id); }

Handle StringType() {
  Handle type(H5Tcopy(H5T_C_S1), CloseType);
  H5Tset_size(type.id(), H5T_VARIABLE);
  H5Tset_cset(type.id(), H5T_CSET_UTF8);
  return type;
}

Handle LinkCreationPlist() {
  Handle plist(H5Pcreate(H5P_LINK_CREATE), ClosePlist);
  H5Pset_create_intermediate_group(plist.id(), 1);
  return plist;
}

}  // namespace

Handle& Handle::operator=(Handle&& other) noexcept {
  if (this != &other) {
    Reset();
    id_ = other.id_;
    closer_ = other.closer_;
    other.id_ = -1;
  }
  return *this;
}

void Handle::Reset() {
  if (id_ >= 0 && closer_) closer_(id_);
  id_ = -1;
}

// ---------------------------------------------------------------- File

File File::Create(const std::filesystem::path& path) {
  SilenceHdf5();
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), ClosePlist);
  H5Pset_fclose_degree(fapl.id(), H5F_CLOSE_STRONG);
  const hid_t id = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.id());
  if (id < 0) ThrowOutputError(path.string(), "cannot create the HDF5 file");
  return File(Handle(id, CloseFile), path);
}

File File::CreateInMemory(const std::filesystem::path& name) {
  SilenceHdf5();
  // Memory grows in steps of this many bytes.
  constexpr std::size_t kMemoryIncrement = std::size_t{1} << 20;
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), ClosePlist);
  H5Pset_fclose_degree(fapl.id(), H5F_CLOSE_STRONG);
  if (H5Pset_fapl_core(fapl.id(), kMemoryIncrement, 0) < 0)
    ThrowOutputError(name.string(), "cannot set up an in-memory file");
  const hid_t id = H5Fcreate(name.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.id());
  if (id < 0) ThrowOutputError(name.string(), "cannot create the HDF5 file in memory");
  return File(Handle(id, CloseFile), name);
}

std::string File::Image() const {
  Flush();
  const ssize_t size = H5Fget_file_image(handle_.id(), nullptr, 0);
  if (size < 0) ThrowOutputError(path_.string(), "cannot get the size of the file image");
  std::string image(static_cast<std::size_t>(size), '\0');
  if (H5Fget_file_image(handle_.id(), image.data(), image.size()) != size) {
    ThrowOutputError(path_.string(), "cannot get the file image");
  }
  return image;
}

File File::Open(const std::filesystem::path& path, bool writable) {
  SilenceHdf5();
  if (!std::filesystem::exists(path)) {
    throw BadInput(fmt::format("{}: no such file; check the path", path.string()));
  }
  struct stat info {};
  if (::stat(path.c_str(), &info) == 0 && !S_ISREG(info.st_mode)) {
    throw BadInput(fmt::format("{}: found {}, expected an HDF5 file; give the path of a regular file", path.string(),
                               DescribeFileType(info.st_mode)));
  }
  if (!IsHdf5(path)) {
    throw BadInput(fmt::format("{}: not an HDF5 file (no HDF5 signature); give a file written by rockfit", path.string()));
  }
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), ClosePlist);
  H5Pset_fclose_degree(fapl.id(), H5F_CLOSE_STRONG);
  const hid_t id = H5Fopen(path.c_str(), writable ? H5F_ACC_RDWR : H5F_ACC_RDONLY, fapl.id());
  if (id < 0) ThrowUnreadable(path.string(), "cannot open the HDF5 file");
  return File(Handle(id, CloseFile), path);
}

bool File::IsHdf5(const std::filesystem::path& path) {
  SilenceHdf5();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return false;
  const htri_t result = H5Fis_hdf5(path.c_str());
  H5Eclear2(H5E_DEFAULT);
  return result > 0;
}

Group File::Root() const {
  const hid_t id = H5Gopen2(handle_.id(), "/", H5P_DEFAULT);
  if (id < 0) ThrowUnreadable(path_.string(), "cannot open the root group");
  return Group(Handle(id, CloseGroup), "/", path_.string());
}

void File::Flush() const {
  if (H5Fflush(handle_.id(), H5F_SCOPE_GLOBAL) < 0) ThrowOutputError(path_.string(), "cannot flush the file");
}

void File::Close() {
  if (!handle_.valid()) return;
  if (H5Fclose(handle_.Release()) < 0) ThrowOutputError(path_.string(), "cannot close the file");
}

// ---------------------------------------------------------------- Group: structure

std::string Group::ChildPath(const std::string& name) const {
  if (!name.empty() && name.front() == '/') return name;
  return path_ == "/" ? "/" + name : path_ + "/" + name;
}

bool Group::Exists(const std::string& name) const {
  // H5Lexists fails on a missing intermediate component: check each one.
  std::string prefix;
  std::size_t start = 0;
  while (start <= name.size()) {
    const std::size_t slash = name.find('/', start);
    const std::string part = name.substr(start, slash == std::string::npos ? std::string::npos : slash - start);
    if (!part.empty()) {
      prefix += (prefix.empty() ? "" : "/") + part;
      if (H5Lexists(handle_.id(), prefix.c_str(), H5P_DEFAULT) <= 0) {
        H5Eclear2(H5E_DEFAULT);
        return false;
      }
    }
    if (slash == std::string::npos) break;
    start = slash + 1;
  }
  return !prefix.empty();
}

Handle Group::OpenObject(const std::string& object) const {
  if (object.empty()) {
    const hid_t id = H5Oopen(handle_.id(), ".", H5P_DEFAULT);
    if (id < 0) ThrowUnreadable(file_name_, fmt::format("cannot open {}", path_));
    return Handle(id, CloseObject);
  }
  if (!Exists(object)) ThrowUnreadable(file_name_, fmt::format("{} does not exist", ChildPath(object)));
  const hid_t id = H5Oopen(handle_.id(), object.c_str(), H5P_DEFAULT);
  if (id < 0) ThrowUnreadable(file_name_, fmt::format("cannot open {}", ChildPath(object)));
  return Handle(id, CloseObject);
}

bool Group::IsGroup(const std::string& name) const {
  if (!Exists(name)) return false;
  const Handle object = OpenObject(name);
  return H5Iget_type(object.id()) == H5I_GROUP;
}

bool Group::IsDataset(const std::string& name) const {
  if (!Exists(name)) return false;
  const Handle object = OpenObject(name);
  return H5Iget_type(object.id()) == H5I_DATASET;
}

Group Group::OpenGroup(const std::string& name) const {
  if (!IsGroup(name)) {
    throw BadInput(fmt::format("{}: no group {}{}", file_name_, ChildPath(name),
                               Exists(name) ? " (it is not a group)" : ""));
  }
  const hid_t id = H5Gopen2(handle_.id(), name.c_str(), H5P_DEFAULT);
  if (id < 0) ThrowUnreadable(file_name_, fmt::format("cannot open group {}", ChildPath(name)));
  return Group(Handle(id, CloseGroup), ChildPath(name), file_name_);
}

Group Group::CreateGroup(const std::string& name) const {
  if (Exists(name)) throw OutputError(fmt::format("{}: {} exists already", file_name_, ChildPath(name)));
  const Handle lcpl = LinkCreationPlist();
  const hid_t id = H5Gcreate2(handle_.id(), name.c_str(), lcpl.id(), H5P_DEFAULT, H5P_DEFAULT);
  if (id < 0) ThrowOutputError(file_name_, fmt::format("cannot create group {}", ChildPath(name)));
  return Group(Handle(id, CloseGroup), ChildPath(name), file_name_);
}

Group Group::OpenOrCreateGroup(const std::string& name) const {
  return Exists(name) ? OpenGroup(name) : CreateGroup(name);
}

void Group::Remove(const std::string& name) const {
  if (!Exists(name)) return;
  if (H5Ldelete(handle_.id(), name.c_str(), H5P_DEFAULT) < 0) {
    ThrowOutputError(file_name_, fmt::format("cannot remove {}", ChildPath(name)));
  }
}

std::vector<std::string> Group::Children() const {
  std::vector<std::string> names;
  hsize_t index = 0;
  const herr_t status = H5Literate(
      handle_.id(), H5_INDEX_NAME, H5_ITER_INC, &index,
      [](hid_t, const char* name, const H5L_info_t*, void* data) -> herr_t {
        static_cast<std::vector<std::string>*>(data)->emplace_back(name);
        return 0;
      },
      &names);
  if (status < 0) ThrowUnreadable(file_name_, fmt::format("cannot list {}", path_));
  return names;
}

// ---------------------------------------------------------------- Group: datasets

namespace {

void WriteDataset(const Group& group, const std::string& name, hid_t memory_type, hid_t file_type,
                  const std::vector<hsize_t>& dims, const void* data, const std::string& units) {
  if (group.Exists(name)) {
    throw OutputError(fmt::format("{}: {} exists already", group.file_name(),
                                  group.path() == "/" ? "/" + name : group.path() + "/" + name));
  }
  Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), CloseSpace);
  const Handle lcpl = LinkCreationPlist();
  Handle dataset(H5Dcreate2(group.id(), name.c_str(), file_type, space.id(), lcpl.id(), H5P_DEFAULT, H5P_DEFAULT),
                 CloseDataset);
  const std::string where = group.path() == "/" ? "/" + name : group.path() + "/" + name;
  if (!dataset.valid()) ThrowOutputError(group.file_name(), fmt::format("cannot create dataset {}", where));
  bool empty = false;
  for (hsize_t d : dims) empty = empty || d == 0;
  if (!empty && H5Dwrite(dataset.id(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0) {
    ThrowOutputError(group.file_name(), fmt::format("cannot write dataset {}", where));
  }
  if (!units.empty()) group.SetString("units", units, name);
}

}  // namespace

void Group::WriteDoubles(const std::string& name, const std::vector<double>& values, const std::string& units) const {
  WriteDataset(*this, name, H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, {values.size()}, values.data(), units);
}

void Group::WriteMatrix(const std::string& name, const std::vector<double>& row_major, std::size_t rows,
                        std::size_t columns, const std::string& units) const {
  if (row_major.size() != rows * columns) {
    throw InvalidArgument(fmt::format("WriteMatrix {}: {} values for {}×{}", name, row_major.size(), rows, columns));
  }
  WriteDataset(*this, name, H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, {rows, columns}, row_major.data(), units);
}

void Group::WriteVectors(const std::string& name, const std::vector<Eigen::Vector3d>& rows,
                         const std::string& units) const {
  std::vector<double> flat;
  flat.reserve(rows.size() * 3);
  for (const auto& v : rows) flat.insert(flat.end(), {v.x(), v.y(), v.z()});
  WriteMatrix(name, flat, rows.size(), 3, units);
}

void Group::WriteInts(const std::string& name, const std::vector<std::int64_t>& values, const std::string& units) const {
  WriteDataset(*this, name, H5T_NATIVE_INT64, H5T_STD_I64LE, {values.size()}, values.data(), units);
}

void Group::WriteStrings(const std::string& name, const std::vector<std::string>& values) const {
  std::vector<const char*> pointers;
  pointers.reserve(values.size());
  for (const auto& v : values) pointers.push_back(v.c_str());
  const Handle type = StringType();
  WriteDataset(*this, name, type.id(), type.id(), {values.size()}, pointers.data(), "");
}

namespace {

struct OpenedDataset {
  Handle dataset;
  Handle space;
  Handle type;  // the stored element type
  std::vector<hsize_t> dims;
  std::size_t count = 0;  // number of elements (checked against the file's size, see below)
  double max_bytes = 0.0;  // the most bytes its values can take when read (kMaxExpansion × the file's size)
};

// A dataset's stored bytes can be compressed, but not by more than this factor: a larger logical size than
// kMaxExpansion × the file's size on disk is a damaged shape, refused before any buffer is allocated for it
// (a damaged header can claim terabytes). Deflate reaches about 1000 on constant data.
constexpr double kMaxExpansion = 4096.0;

OpenedDataset OpenDataset(const Group& group, const std::string& name) {
  const std::string where = group.path() == "/" ? "/" + name : group.path() + "/" + name;
  if (!group.IsDataset(name)) {
    throw BadInput(fmt::format("{}: no dataset {}{}", group.file_name(), where,
                               group.Exists(name) ? " (it is a group)" : ""));
  }
  OpenedDataset out;
  out.dataset = Handle(H5Dopen2(group.id(), name.c_str(), H5P_DEFAULT), CloseDataset);
  if (!out.dataset.valid()) ThrowUnreadable(group.file_name(), fmt::format("cannot open dataset {}", where));
  out.space = Handle(H5Dget_space(out.dataset.id()), CloseSpace);
  const int rank = H5Sget_simple_extent_ndims(out.space.id());
  if (rank < 0) ThrowUnreadable(group.file_name(), fmt::format("cannot read the shape of {}", where));
  out.dims.resize(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(out.space.id(), out.dims.data(), nullptr);
  // The element count, with the bytes it needs (8 per value at most as rockfit reads it) bounded by the file.
  hsize_t file_bytes = 0;
  const Handle file(H5Iget_file_id(out.dataset.id()), CloseFile);
  if (!file.valid() || H5Fget_filesize(file.id(), &file_bytes) < 0) {
    ThrowUnreadable(group.file_name(), fmt::format("cannot read the size of the file holding {}", where));
  }
  out.max_bytes = kMaxExpansion * static_cast<double>(file_bytes);
  const double max_count = out.max_bytes / 8.0;
  double count = 1.0;
  for (hsize_t d : out.dims) count *= static_cast<double>(d);
  if (!(count <= max_count)) {
    std::string shape;
    for (hsize_t d : out.dims) shape += (shape.empty() ? "" : " × ") + std::to_string(d);
    throw BadInput(fmt::format("{}: dataset {} claims a shape of {} values in a file of {} bytes: the file is damaged; "
                               "write it again with rockfit or restore a copy",
                               group.file_name(), where, shape, file_bytes));
  }
  out.count = static_cast<std::size_t>(count);
  // Values stored in the object header (compact layout) or in one block (contiguous) take exactly count × the stored
  // element size; a damaged header can claim a shape its storage does not hold, and Debian's libhdf5 1.10 then reads
  // through a null pointer in H5Dread (a crash, not an error). Refused here, before any read. (Chunked storage can be
  // compressed, and a contiguous block never written holds no bytes: the library reads the fill value, safely.)
  const Handle creation(H5Dget_create_plist(out.dataset.id()), ClosePlist);
  out.type = Handle(H5Dget_type(out.dataset.id()), CloseType);
  if (!creation.valid() || !out.type.valid()) {
    ThrowUnreadable(group.file_name(), fmt::format("cannot read how {} is stored", where));
  }
  const H5D_layout_t layout = H5Pget_layout(creation.id());
  const double needed_bytes = count * static_cast<double>(H5Tget_size(out.type.id()));
  const double stored_bytes = static_cast<double>(H5Dget_storage_size(out.dataset.id()));
  const bool one_block = layout == H5D_COMPACT || (layout == H5D_CONTIGUOUS && stored_bytes > 0.0);
  if (out.count > 0 && one_block && stored_bytes < needed_bytes) {
    throw BadInput(fmt::format("{}: dataset {} stores {} bytes where its shape needs {}: the file is damaged; write it "
                               "again with rockfit or restore a copy",
                               group.file_name(), where, stored_bytes, needed_bytes));
  }
  return out;
}

}  // namespace

std::vector<std::size_t> Group::Shape(const std::string& name) const {
  const OpenedDataset d = OpenDataset(*this, name);
  return std::vector<std::size_t>(d.dims.begin(), d.dims.end());
}

std::vector<double> Group::ReadDoubles(const std::string& name, std::vector<std::size_t>* shape) const {
  const OpenedDataset d = OpenDataset(*this, name);
  const H5T_class_t type_class = H5Tget_class(d.type.id());
  if (type_class != H5T_FLOAT && type_class != H5T_INTEGER) {
    throw BadInput(fmt::format("{}: dataset {} is not numeric", file_name_, ChildPath(name)));
  }
  std::vector<double> values(d.count);
  if (!values.empty() &&
      H5Dread(d.dataset.id(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0) {
    ThrowUnreadable(file_name_, fmt::format("cannot read dataset {}", ChildPath(name)));
  }
  if (shape) shape->assign(d.dims.begin(), d.dims.end());
  return values;
}

std::vector<Eigen::Vector3d> Group::ReadVectors(const std::string& name) const {
  std::vector<std::size_t> shape;
  const std::vector<double> flat = ReadDoubles(name, &shape);
  if (shape.size() != 2 || shape[1] != 3) {
    std::string found;
    for (std::size_t d : shape) found += (found.empty() ? "" : ", ") + std::to_string(d);
    throw BadInput(fmt::format("{}: dataset {} has shape ({}), expected (N, 3)", file_name_, ChildPath(name), found));
  }
  std::vector<Eigen::Vector3d> rows(shape[0]);
  for (std::size_t i = 0; i < shape[0]; ++i) rows[i] = {flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]};
  return rows;
}

std::vector<std::int64_t> Group::ReadInts(const std::string& name) const {
  const OpenedDataset d = OpenDataset(*this, name);
  if (H5Tget_class(d.type.id()) != H5T_INTEGER) {
    throw BadInput(fmt::format("{}: dataset {} is not an integer dataset", file_name_, ChildPath(name)));
  }
  std::vector<std::int64_t> values(d.count);
  if (!values.empty() &&
      H5Dread(d.dataset.id(), H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0) {
    ThrowUnreadable(file_name_, fmt::format("cannot read dataset {}", ChildPath(name)));
  }
  return values;
}

std::vector<std::string> Group::ReadStrings(const std::string& name) const {
  const OpenedDataset d = OpenDataset(*this, name);
  const Handle& file_type = d.type;
  if (H5Tget_class(file_type.id()) != H5T_STRING) {
    throw BadInput(fmt::format("{}: dataset {} does not hold strings", file_name_, ChildPath(name)));
  }
  const std::size_t n = d.count;
  std::vector<std::string> values;
  values.reserve(n);
  if (n == 0) return values;
  if (H5Tis_variable_str(file_type.id()) > 0) {
    const Handle type = StringType();
    std::vector<char*> pointers(n, nullptr);
    if (H5Dread(d.dataset.id(), type.id(), H5S_ALL, H5S_ALL, H5P_DEFAULT, pointers.data()) < 0) {
      ThrowUnreadable(file_name_, fmt::format("cannot read dataset {}", ChildPath(name)));
    }
    for (char* p : pointers) values.emplace_back(p ? p : "");
    H5Dvlen_reclaim(type.id(), d.space.id(), H5P_DEFAULT, pointers.data());
  } else {
    const std::size_t width = H5Tget_size(file_type.id());
    if (!(static_cast<double>(n) * static_cast<double>(width) <= d.max_bytes)) {
      throw BadInput(fmt::format("{}: dataset {} claims {} strings of {} bytes, more than its file can hold: the file is "
                                 "damaged; write it again with rockfit or restore a copy",
                                 file_name_, ChildPath(name), n, width));
    }
    std::vector<char> buffer(n * width);
    if (H5Dread(d.dataset.id(), file_type.id(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer.data()) < 0) {
      ThrowUnreadable(file_name_, fmt::format("cannot read dataset {}", ChildPath(name)));
    }
    for (std::size_t i = 0; i < n; ++i) {
      const char* begin = buffer.data() + i * width;
      values.emplace_back(begin, strnlen(begin, width));
    }
  }
  return values;
}

// ---------------------------------------------------------------- Group: attributes

namespace {

void WriteAttribute(const Group& group, const Handle& object, const std::string& attribute, hid_t memory_type,
                    hid_t file_type, const void* data, const std::string& where) {
  if (H5Aexists(object.id(), attribute.c_str()) > 0) H5Adelete(object.id(), attribute.c_str());
  Handle space(H5Screate(H5S_SCALAR), CloseSpace);
  Handle attr(H5Acreate2(object.id(), attribute.c_str(), file_type, space.id(), H5P_DEFAULT, H5P_DEFAULT),
              CloseAttribute);
  if (!attr.valid() || H5Awrite(attr.id(), memory_type, data) < 0) {
    ThrowOutputError(group.file_name(), fmt::format("cannot write attribute '{}' of {}", attribute, where));
  }
}

}  // namespace

void Group::SetString(const std::string& attribute, const std::string& value, const std::string& object) const {
  const Handle target = OpenObject(object);
  const Handle type = StringType();
  const char* pointer = value.c_str();
  WriteAttribute(*this, target, attribute, type.id(), type.id(), &pointer, ChildPath(object));
}

void Group::SetDouble(const std::string& attribute, double value, const std::string& object) const {
  const Handle target = OpenObject(object);
  WriteAttribute(*this, target, attribute, H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, &value, ChildPath(object));
}

void Group::SetInt(const std::string& attribute, std::int64_t value, const std::string& object) const {
  const Handle target = OpenObject(object);
  WriteAttribute(*this, target, attribute, H5T_NATIVE_INT64, H5T_STD_I64LE, &value, ChildPath(object));
}

bool Group::HasAttribute(const std::string& attribute, const std::string& object) const {
  if (!object.empty() && !Exists(object)) return false;
  const Handle target = OpenObject(object);
  return H5Aexists(target.id(), attribute.c_str()) > 0;
}

namespace {

// Opens a scalar (or one-element) attribute; empty Handle when absent.
Handle OpenAttribute(const Handle& object, const std::string& attribute) {
  if (H5Aexists(object.id(), attribute.c_str()) <= 0) return Handle();
  return Handle(H5Aopen(object.id(), attribute.c_str(), H5P_DEFAULT), CloseAttribute);
}

}  // namespace

std::optional<std::string> Group::GetString(const std::string& attribute, const std::string& object) const {
  if (!object.empty() && !Exists(object)) return std::nullopt;
  const Handle target = OpenObject(object);
  const Handle attr = OpenAttribute(target, attribute);
  if (!attr.valid()) return std::nullopt;
  const Handle file_type(H5Aget_type(attr.id()), CloseType);
  if (H5Tget_class(file_type.id()) != H5T_STRING) {
    throw BadInput(fmt::format("{}: attribute '{}' of {} is not a string", file_name_, attribute, ChildPath(object)));
  }
  if (H5Tis_variable_str(file_type.id()) > 0) {
    const Handle type = StringType();
    char* pointer = nullptr;
    if (H5Aread(attr.id(), type.id(), &pointer) < 0) {
      ThrowUnreadable(file_name_, fmt::format("cannot read attribute '{}' of {}", attribute, ChildPath(object)));
    }
    std::string value = pointer ? pointer : "";
    H5free_memory(pointer);
    return value;
  }
  const std::size_t width = H5Tget_size(file_type.id());
  std::vector<char> buffer(width + 1, '\0');
  if (H5Aread(attr.id(), file_type.id(), buffer.data()) < 0) {
    ThrowUnreadable(file_name_, fmt::format("cannot read attribute '{}' of {}", attribute, ChildPath(object)));
  }
  return std::string(buffer.data(), strnlen(buffer.data(), width));
}

std::optional<double> Group::GetDouble(const std::string& attribute, const std::string& object) const {
  if (!object.empty() && !Exists(object)) return std::nullopt;
  const Handle target = OpenObject(object);
  const Handle attr = OpenAttribute(target, attribute);
  if (!attr.valid()) return std::nullopt;
  double value = 0.0;
  if (H5Aread(attr.id(), H5T_NATIVE_DOUBLE, &value) < 0) {
    ThrowUnreadable(file_name_, fmt::format("attribute '{}' of {} is not a number", attribute, ChildPath(object)));
  }
  return value;
}

std::optional<std::int64_t> Group::GetInt(const std::string& attribute, const std::string& object) const {
  if (!object.empty() && !Exists(object)) return std::nullopt;
  const Handle target = OpenObject(object);
  const Handle attr = OpenAttribute(target, attribute);
  if (!attr.valid()) return std::nullopt;
  std::int64_t value = 0;
  if (H5Aread(attr.id(), H5T_NATIVE_INT64, &value) < 0) {
    ThrowUnreadable(file_name_, fmt::format("attribute '{}' of {} is not an integer", attribute, ChildPath(object)));
  }
  return value;
}

// ---------------------------------------------------------------- copies

void CopyObject(const Group& from, const std::string& name, const Group& to) {
  if (H5Ocopy(from.id(), name.c_str(), to.id(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT) < 0) {
    ThrowOutputError(to.file_name(), fmt::format("cannot copy {} from {}", name, from.file_name()));
  }
}

void CopyAttributes(const Group& from, const Group& to) {
  struct Context {
    hid_t target;
    const Group* to;
  } context{to.id(), &to};
  hsize_t index = 0;
  const herr_t status = H5Aiterate2(
      from.id(), H5_INDEX_NAME, H5_ITER_INC, &index,
      [](hid_t location, const char* name, const H5A_info_t*, void* data) -> herr_t {
        auto* ctx = static_cast<Context*>(data);
        Handle attr(H5Aopen(location, name, H5P_DEFAULT), CloseAttribute);
        Handle file_type(H5Aget_type(attr.id()), CloseType);
        Handle space(H5Aget_space(attr.id()), CloseSpace);
        Handle memory_type(H5Tget_native_type(file_type.id(), H5T_DIR_DEFAULT), CloseType);
        const auto points = static_cast<std::size_t>(H5Sget_simple_extent_npoints(space.id()));
        std::vector<unsigned char> buffer(std::max<std::size_t>(1, points) * H5Tget_size(memory_type.id()));
        if (!attr.valid() || H5Aread(attr.id(), memory_type.id(), buffer.data()) < 0) return -1;
        if (H5Aexists(ctx->target, name) > 0) H5Adelete(ctx->target, name);
        Handle copy(H5Acreate2(ctx->target, name, file_type.id(), space.id(), H5P_DEFAULT, H5P_DEFAULT), CloseAttribute);
        const herr_t written = copy.valid() ? H5Awrite(copy.id(), memory_type.id(), buffer.data()) : -1;
        if (H5Tdetect_class(memory_type.id(), H5T_VLEN) > 0 || H5Tis_variable_str(memory_type.id()) > 0) {
          H5Dvlen_reclaim(memory_type.id(), space.id(), H5P_DEFAULT, buffer.data());
        }
        return written < 0 ? -1 : 0;
      },
      &context);
  if (status < 0) ThrowOutputError(to.file_name(), fmt::format("cannot copy the attributes of {}", from.path()));
}

}  // namespace rockfit::io::hdf5
