// A longer window when the first one leaves λ_lat undetermined (fitting/README.md, "End of the fitting window").
//
// The window ends just before the first return impact after the first impact (initial_guess.hpp). λ_lat acts at
// facet impacts only ((18), (21)); a block released with a roll lands on a corner, rocks on vertices and edges,
// and its first facet impact can come at or after that return impact. The window then holds no facet impact, the
// fit leaves λ_lat anywhere in its bounds (`determined` no), and the model's later lateral motion — which the
// whole-recording metrics (OPMF) see — is a guess. The fitter then fits again on windows ending just before the
// next return impacts (the objective's later window ends, trial_problem.hpp), one at a time, from the previous
// fit's point, until λ_lat is determined, at most max_extensions times. A fit whose λ_lat the first window
// determines (or fixes) is never refitted.
#pragma once

#include <string>
#include <vector>

#include "rockfit/fitting/objective.hpp"
#include "rockfit/fitting/parameters.hpp"

namespace rockfit::fitting {

struct WindowExtensionOptions {
  bool enabled = true;
  // At most this many later return impacts: each extension is a whole fit (global stage, intervals), and beyond
  // a few rocking cycles the model error of a real block accumulates in the phase of the motion.
  int max_extensions = 3;
  // λ_lat and λ_lon act at facet impacts only, so the window that left λ_lat undetermined left their values
  // arbitrary; a longer window's fit also starts from λ_lat = 0 with λ_lon the best of this many values evenly
  // over its bounds (the other parameters held), when (28) is lower there than at the previous fit's point
  // (0: not). 61 points step 0.05 over the empirical bounds [−0.5, 2.5].
  int lambda_lon_scan_points = 61;
  void Validate() const;  // throws InvalidArgument
};

// What became of the window: where it ended first and at the end, and why (JSON "window", HDF5 attributes,
// the table).
struct WindowReport {
  double first_t_end_s = 0.0;  // the window of the first fit (recording time)
  double t_end_s = 0.0;        // the window of the kept fit
  int extensions = 0;          // later return impacts added to the kept fit's window (0: the first window)
  int extensions_tried = 0;    // fits on longer windows (kept or not)
  std::vector<double> tried_t_end_s;  // their window ends (recording time), in order
  // "lambda_lat determined", "lambda_lat fixed", "lambda_lat determined by the extension", "lambda_lat not
  // determined by any extension", "no later return impact", "extension off"
  std::string reason;
};

// The start of the fit on a longer window: `previous` (the last fit's point), or — when λ_lon is free and
// options.lambda_lon_scan_points > 0 — the same with λ_lat = 0 (clamped to its bounds, if free) and λ_lon scanned
// over its bounds, whichever has the lower (28) on `longer`'s window. Never throws for numerical trouble.
ParameterSet StartOnLongerWindow(const Objective& longer, const ParameterSet& previous,
                                 const WindowExtensionOptions& options);

// {"first_t_end", "t_end", "extensions", "extensions_tried", "tried_t_end", "reason"} for the fit JSON.
std::string WindowReportJson(const WindowReport& report);

// One line for tables: "ends at T s (…)", with the first window and the fits tried when it was extended.
std::string WindowReportText(const WindowReport& report);

}  // namespace rockfit::fitting
