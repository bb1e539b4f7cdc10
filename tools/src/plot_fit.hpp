// Figures of fits (DESIGN §10): the measured and simulated angular velocity of one trial (the paper's Fig. 14)
// and the fitted parameters of a campaign per block and position (Fig. 15). `rockfit plot fit` and
// `rockfit plot parameters` (registered in plot_fit.cpp) and `rockfit fit --plot` draw them.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rockfit/fitting/fit_store.hpp"
#include "rockfit/fitting/trial_fit.hpp"

namespace rockfit::tools {

struct FitFigureData {
  std::string trial_id;
  std::vector<double> t_s;
  std::vector<Eigen::Vector3d> w_measured_B;
  std::vector<Eigen::Vector3d> w_simulated_B;
  std::vector<double> impact_t_s;        // the model's impacts
  std::vector<std::string> impact_kind;
  std::string caption;                    // parameters and ε
};

FitFigureData FitFigureFrom(const fitting::StoredFit& fit);
FitFigureData FitFigureFrom(const fitting::TrialFit& fit, const std::string& trial_id);

// Three panels (ω_x, ω_y, ω_z): measured as dots, simulated as lines, impacts as vertical marks.
void RenderFitFigure(const FitFigureData& data, const std::filesystem::path& output, int width_px, int height_px);

}  // namespace rockfit::tools
