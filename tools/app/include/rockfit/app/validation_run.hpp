// What `rockfit validate` and the Python module share: the predictive check of a campaign manifest
// (fitting/predictive_check.hpp) from own fits read from a `rockfit batch` file or fitted now, and its table.
#pragma once

#include <string>

#include "rockfit/app/fit_setup.hpp"
#include "rockfit/fitting/predictive_check.hpp"

namespace rockfit::app {

struct ValidateArgs {
  std::string manifest;
  std::string fits;   // a file of `rockfit batch` with /fits/<trial> of every trial; empty: fit them now
  FitArgs fit;        // settings of the own fits made now and of every trial's problem
  int jobs = 0;       // trials at once (0: all cores)
  double ratio_warning = 1.5;
};

// Own fits (read or made), then the leave-one-out predictions. InvalidArgument for bad options, BadInput for an
// unreadable manifest or a fits file without a trial of the manifest.
fitting::ValidationSummary RunValidation(const ValidateArgs& args);

// Per trial ε_own, ε_pred, ratio and the overlaps (and the refitted release roll β in mrad, a column only where some
// trial fits it), then per group the median and largest ratio.
std::string ValidationTable(const fitting::ValidationSummary& summary);

}  // namespace rockfit::app
