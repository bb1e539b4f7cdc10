#include "rockfit/fitting/version.hpp"
namespace rockfit::fitting {
const char* FitSchemaVersion() { return "1"; }
}  // namespace rockfit::fitting
