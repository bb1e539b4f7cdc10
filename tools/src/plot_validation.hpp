// The figure of the predictive check (`rockfit validate --plot`, `rockfit plot validation FILE`): ε_pred/ε_own per
// trial, grouped by block and position, filled where the trial's own 95 % intervals of λ, λ_lat, λ_lon overlap the
// others' pooled ones, with lines at 1 and at the warning ratio.
#pragma once

#include <filesystem>

#include "rockfit/fitting/predictive_check.hpp"

namespace rockfit::tools {

// OutputError when gnuplot is missing or fails; InvalidArgument for an output that is not .png or .svg.
void RenderValidationPlot(const fitting::ValidationSummary& summary, const std::filesystem::path& output, int width_px,
                          int height_px);

}  // namespace rockfit::tools
