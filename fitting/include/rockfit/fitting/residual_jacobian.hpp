// The per-node residuals of (28) that the least-squares back end fits, and their exact Jacobian from the model's
// sensitivities (fitting/README.md, "Ceres back end").
//
// Node i of the window [t0, t_end] has the residual f_i = s_i (ω_m,i − ω_s(t_i − t0)) with a scale s_i that depends
// on its trapezoid weight w_i and the window T = t_end − t0:
//   soft-L1:       s_i = (T_ref/T)·w_i/√Δt   (the Ceres cost then approaches c·T_ref·ε of (28)),
//   least squares: s_i = √w_i                (the Gauss–Newton covariance).
// A model parameter p enters only through ω_s: ∂f_i/∂p = −s_i ∂ω_s/∂p. The release time t0 moves the first
// node (ω_m interpolated at t0), the weights of the first two nodes (∂w_0/∂t0 = ∂w_1/∂t0 = −½), the window
// (∂T/∂t0 = −1) and the model's time at every later node (∂ω_s(t_i − t0)/∂t0 = −ω̇_s):
//   ∂f_i/∂t0 = (∂s_i/∂t0)(ω_m,i − ω_s,i) + s_i (∂ω_m,i/∂t0 + [i ≥ 1] ω̇_s,i).
// This holds between the points where t0 crosses a sample time (the node set changes there; (28) stays
// continuous but its derivative does not).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "rockfit/fitting/objective.hpp"

namespace rockfit::fitting {

struct ResidualScale {
  enum class Kind { kSoftL1, kLeastSquares };
  Kind kind = Kind::kLeastSquares;
  double t_ref_s = 1.0;         // soft-L1 only: the window at the start of the search
  double nominal_dt_s = 1.0;    // soft-L1 only: the nominal sample interval
  double Scale(double weight_s, double window_s) const;
  // ∂s/∂t0 for a node whose weight changes by dweight_dt0 with t0.
  double ScaleDerivativeT0(double weight_s, double dweight_dt0, double window_s) const;
};

// One node's residual (3) and its derivatives with respect to the free parameters (3 × free, in free_ids() order).
struct NodeResidual {
  Eigen::Vector3d f = Eigen::Vector3d::Zero();
  Eigen::Matrix<double, 3, Eigen::Dynamic> df_dx;
};

struct ResidualJacobianSummary {
  bool available = false;
  std::string reason;  // why not (empty when available)
};

// The residuals of every node of `nodes` and their exact Jacobian from output.dw_B_dparams (the model run at
// `values` with sensitivities). Not available when the model gave no sensitivities, or when a free parameter has
// none (NaN column, τ_edge).
ResidualJacobianSummary NodeResiduals(const Objective& objective, const ErrorNodes& nodes, const ModelOutput& output,
                                      const ResidualScale& scale, std::vector<NodeResidual>* residuals);

}  // namespace rockfit::fitting
