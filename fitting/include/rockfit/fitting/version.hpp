#pragma once
namespace rockfit::fitting {
// Version of the fitting library's file layout (/fits in HDF5).
const char* FitSchemaVersion();
}  // namespace rockfit::fitting
