// The one entry point for reading a recording (docs/design.md §5): detect the format from the path (or take
// LoadOptions::format), run its reader, return a Recording in SI units and block axes.
#pragma once

#include <filesystem>

#include "rockfit/io/load_options.hpp"
#include "rockfit/io/recording.hpp"

namespace rockfit::io {

// Throws BadInput for data that cannot be used (message: file, line, column, found, expected, what
// to do) and InvalidArgument for options that do not fit (e.g. a column map for an x-IMU file).
Recording LoadRecording(const std::filesystem::path& path, const LoadOptions& options = {});

}  // namespace rockfit::io
