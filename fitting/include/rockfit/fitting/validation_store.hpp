// The predictive check's part of an HDF5 file (predictive_check.hpp; layout in fitting/README.md, "Predictive
// check", and docs/file-formats.md §5): /validation/per_trial and /validation/per_group as parallel columns,
// with the check's settings as attributes of /validation. The writer takes the root of an open file (the caller
// wraps it in an io::hdf5::Transaction that replaces /validation).
#pragma once

#include <string>

#include "rockfit/fitting/predictive_check.hpp"
#include "rockfit/io/hdf5_file.hpp"

namespace rockfit::fitting {

// A trial's own fit as stored in /fits/<trial> (fit_store.hpp) by `rockfit batch` or `rockfit fit -o`: values,
// 95 % intervals, `determined` yes, ε, feasible. BadInput when the file has no such group.
OwnFit ReadOwnFit(const io::hdf5::Group& root, const std::string& trial);

void WriteValidationGroup(const io::hdf5::Group& root, const ValidationSummary& summary);

// /validation/per_trial read back (for figures): trial, block, position, ε_own, ε_pred, ratio, overlaps_all and
// the ratio_warning attribute. Unpredicted trials read NaN ratios. BadInput when the file has no /validation.
ValidationSummary ReadValidationGroup(const io::hdf5::Group& root);

}  // namespace rockfit::fitting
