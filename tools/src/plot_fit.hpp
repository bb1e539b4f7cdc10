// The fit picture (paper Fig. 14): measured ω as dots, simulated ω as lines, one panel per component, the
// model's impacts as vertical marks. Used by `rockfit plot fit` and `rockfit fit --plot`.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rockfit/core/simulator.hpp"

namespace rockfit::tools {

struct FitPlotData {
  std::string trial;
  std::vector<double> t_s;                    // the nodes of (28) (recording time)
  std::vector<Eigen::Vector3d> w_measured_B;  // [rad/s]
  std::vector<Eigen::Vector3d> w_simulated_B; // [rad/s]; empty when the model failed
  std::vector<double> impact_t_s;
  std::vector<core::ImpactKind> impact_kind;
  double epsilon_rad_s = 0.0;
  // One line per free parameter: "t0 = 1.2001 s [1.1995, 1.2008]" (value and 95 % interval), shown under the
  // title; empty for fits without intervals.
  std::vector<std::string> parameter_lines;
};

// The parameter lines of FitPlotData from names, units, values, fixed flags and 95 % interval ends (NaN: open).
std::vector<std::string> ParameterLines(const std::vector<std::string>& names, const std::vector<std::string>& units,
                                        const std::vector<double>& values, const std::vector<bool>& fixed,
                                        const std::vector<double>& lower_95, const std::vector<double>& upper_95);

// OutputError when gnuplot is missing or fails.
void RenderFitPlot(const FitPlotData& data, const std::filesystem::path& output, int width_px, int height_px);

}  // namespace rockfit::tools
