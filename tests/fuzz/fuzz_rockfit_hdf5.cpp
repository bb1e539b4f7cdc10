// libFuzzer target: rockfit's HDF5 store, read as `rockfit inspect FILE.h5`, `rockfit correct FILE.h5
// --trial ID` and `rockfit plot summary FILE.h5` read it (io::ListTrialsHdf5, io::ReadTrialHdf5,
// io::ReadRecordingHdf5, io::ReadSummaryHdf5). The input is the whole file; the seed corpus holds
// files rockfit wrote, so mutations land in real superblocks, object headers and datasets.
// The HDF5 library itself (Debian's libhdf5, not instrumented) is outside what this target proves:
// see tests/fuzz/README.md for how its own crashes are told apart from rockfit's.
#include <cstddef>
#include <cstdint>

#include "rockfit_hdf5_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rockfit::fuzz::RockfitHdf5(rockfit::fuzz::AsText(data, size));
  return 0;
}
