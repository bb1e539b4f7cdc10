#include "rockfit/core/general_impact_map.hpp"

#include "detail/conditioned_solve.hpp"
#include "rockfit/core/enum_names.hpp"

namespace rockfit::core {

const char* ToString(ImpactStatus status) {
  switch (status) {
    case ImpactStatus::kOk: return "ok";
    case ImpactStatus::kInfeasible: return "infeasible";
    case ImpactStatus::kAmbiguous: return "ambiguous";
    case ImpactStatus::kSingular: return "singular";
  }
  return "unknown";
}

bool FromString(std::string_view text, ImpactStatus* value) {
  static constexpr ImpactStatus kAll[] = {ImpactStatus::kOk, ImpactStatus::kInfeasible, ImpactStatus::kAmbiguous, ImpactStatus::kSingular};
  return core::FromStringAmong(text, kAll, value);
}

Eigen::Matrix3d SkewOf(const Eigen::Vector3d& p_x, const Eigen::Vector3d& p_C) {
  // (14): built from d = r_x − r_c, so that R_x ω = d × ω = ω × (r_c − r_x), as (15)–(16) need.
  const Eigen::Vector3d d = p_x - p_C;
  Eigen::Matrix3d R_x;
  R_x << 0.0, -d.z(), d.y(),
         d.z(), 0.0, -d.x(),
         -d.y(), d.x(), 0.0;
  return R_x;
}

MapResult GeneralImpactMap(const ImpactGeometry& g, const Eigen::Vector3d& w_minus, double tau) {
  const Eigen::Matrix3d R_R = SkewOf(g.p_R, g.p_C);
  const Eigen::Matrix3d lhs = g.inertia_C - g.mass_kg * R_R * SkewOf(g.p_a, g.p_C);  // Θ − m R_R R_a
  const Eigen::Vector3d rhs =
      (g.inertia_C - g.mass_kg * R_R * SkewOf(g.p_b, g.p_C)) * w_minus + tau * Eigen::Vector3d::UnitZ();
  MapResult result;
  Eigen::Vector3d w_plus;
  if (!detail::SolveConditioned3(lhs, rhs, kImpactMinReciprocalCondition, &w_plus)) {  // (18)
    result.status = ImpactStatus::kSingular;
    return result;
  }
  result.w_plus = w_plus;
  return result;
}

double KineticEnergyAbout(const ImpactGeometry& g, const Eigen::Vector3d& p_x, const Eigen::Vector3d& w) {
  const Eigen::Matrix3d R_x = SkewOf(p_x, g.p_C);
  return 0.5 * w.dot((g.inertia_C + g.mass_kg * R_x.transpose() * R_x) * w);  // Sect. 4.8
}

}  // namespace rockfit::core
