// The kind of a file named on the command line, from its extension in any case (".H5" is ".h5"): one rule
// for every command that writes rockfit HDF5 or CSV, reads a campaign or draws a picture.
#pragma once

#include <filesystem>
#include <string>

namespace rockfit::app {

// The extension of `path` in lower case, with its dot (".h5"); empty when there is none.
std::string LowerCaseExtension(const std::filesystem::path& path);

enum class OutputKind { kHdf5, kCsv };

// .h5/.hdf5 → kHdf5, .csv → kCsv; InvalidArgument naming `-o output` for anything else.
OutputKind OutputKindFor(const std::string& output);

}  // namespace rockfit::app
