#include "rockfit/app/output_kind.hpp"

#include <algorithm>
#include <cctype>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"

namespace rockfit::app {

std::string LowerCaseExtension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

OutputKind OutputKindFor(const std::string& output) {
  const std::string ext = LowerCaseExtension(output);
  if (ext == ".h5" || ext == ".hdf5") return OutputKind::kHdf5;
  if (ext == ".csv") return OutputKind::kCsv;
  throw InvalidArgument(fmt::format("-o {}: the output must end in .h5/.hdf5 (rockfit HDF5) or .csv", output));
}

}  // namespace rockfit::app
