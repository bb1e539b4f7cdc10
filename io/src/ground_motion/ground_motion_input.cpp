#include "rockfit/io/ground_motion_input.hpp"

#include <algorithm>
#include <cmath>

#include "rockfit/core/errors.hpp"
#include "text/input_problem.hpp"

namespace rockfit::io {
namespace {

// Two components have the same step when they differ by less than this fraction of it.
constexpr double kSameStepRelTol = 1e-9;

}  // namespace

AssembledGroundMotion AssembleGroundMotion(const GroundMotionAssembly& assembly) {
  const std::optional<RecordComponent>* parts[3] = {&assembly.horizontal_1, &assembly.horizontal_2, &assembly.vertical};
  const RecordComponent* reference = nullptr;
  std::size_t length = 0;
  for (const auto* part : parts) {
    if (!part->has_value()) continue;
    const RecordComponent& c = **part;
    if (c.accel_m_s2.size() < 2) throw InvalidArgument("the record " + c.source + " has fewer than two samples");
    if (reference == nullptr) {
      reference = &c;
    } else if (std::abs(c.dt_s - reference->dt_s) > kSameStepRelTol * reference->dt_s) {
      ThrowBadInput({{c.source}, "time step", "DT = " + std::to_string(c.dt_s) + " s",
                     "the step of " + reference->source + ", " + std::to_string(reference->dt_s) + " s",
                     "Combine only components recorded together, or resample one of them."});
    }
    length = std::max(length, c.accel_m_s2.size());
  }
  if (reference == nullptr) throw InvalidArgument("give at least one ground-motion component");
  if (!std::isfinite(assembly.incidence_rad)) throw InvalidArgument("the incidence angle must be finite");
  if (assembly.target_pga_m_s2 && !(*assembly.target_pga_m_s2 > 0.0 && std::isfinite(*assembly.target_pga_m_s2))) {
    throw InvalidArgument("the target PGA must be a positive number");
  }
  if (!std::isfinite(assembly.scale)) throw InvalidArgument("the scale factor must be finite");

  AssembledGroundMotion out;
  std::vector<Eigen::Vector3d> a(length, Eigen::Vector3d::Zero());
  for (int axis = 0; axis < 3; ++axis) {
    if (!parts[axis]->has_value()) continue;
    const RecordComponent& c = **parts[axis];
    for (std::size_t k = 0; k < c.accel_m_s2.size(); ++k) a[k][axis] = c.accel_m_s2[k];
    if (c.accel_m_s2.size() < length) {
      out.notes.push_back(c.source + " has " + std::to_string(c.accel_m_s2.size()) + " samples, padded with zeros to " +
                          std::to_string(length));
    }
  }
  const core::GroundMotion unscaled = core::GroundMotion::Uniform(reference->dt_s, std::move(a)).Rotated(assembly.incidence_rad);
  out.scale = assembly.scale;
  if (assembly.target_pga_m_s2) {
    const bool horizontal = assembly.horizontal_1.has_value() || assembly.horizontal_2.has_value();
    const double peak = horizontal ? unscaled.PeakHorizontal() : unscaled.PeakVertical();
    if (!(peak > 0.0)) throw InvalidArgument("the record is zero everywhere: it cannot be scaled to a target PGA");
    out.scale = *assembly.target_pga_m_s2 / peak;
  }
  out.ground = unscaled.Scaled(out.scale);
  return out;
}

}  // namespace rockfit::io
