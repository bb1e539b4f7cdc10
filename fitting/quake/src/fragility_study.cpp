#include "rockfit/quake/fragility_study.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string_view>
#include <type_traits>

#include <fmt/format.h>

#include "parallel_for.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/quake/binomial_interval.hpp"
#include "rockfit/io/content_hash.hpp"
#include "rockfit/io/synth_random.hpp"
#include "rockfit/core/enum_names.hpp"

namespace rockfit::quake {
namespace {

static_assert(std::is_trivially_copyable_v<SampleOutcome>, "outcomes travel as bytes");
static_assert(sizeof(SampleOutcome) == 160, "SampleOutcome has no padding: its bytes are its values");

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kTwoPi = 6.283185307179586476925286766559;
constexpr double kConfidence = 0.95;

std::string RecordHash(const core::GroundMotion& g) {
  const auto& a = g.samples_W();
  const std::string_view bytes(reinterpret_cast<const char*>(a.data()), a.size() * sizeof(Eigen::Vector3d));
  return io::HashHex(io::Fnv1a64(bytes));
}

}  // namespace

const char* ToString(IntensityMeasure measure) { return measure == IntensityMeasure::kPga ? "pga_g" : "scale"; }

bool FromString(std::string_view text, IntensityMeasure* value) {
  static constexpr IntensityMeasure kAll[] = {IntensityMeasure::kPga, IntensityMeasure::kScale};
  return core::FromStringAmong(text, kAll, value);
}

std::string TiltLimitStateName(double fraction) { return fmt::format("tilt_{}", fraction); }

void FragilityStudyOptions::Validate() const {
  if (blocks.empty()) throw InvalidArgument("a fragility study needs at least one block");
  for (const FragilityBlock& b : blocks) {
    for (const ParameterDistribution* d : {&b.lambda, &b.lambda_lat, &b.lambda_lon}) {
      if (!std::isfinite(d->mean) || !std::isfinite(d->sd) || d->sd < 0.0) {
        throw InvalidArgument(fmt::format("block {}: a parameter distribution needs a finite mean and a standard "
                                          "deviation ≥ 0, got {} ± {}", b.id, d->mean, d->sd));
      }
    }
  }
  if (records.empty()) throw InvalidArgument("a fragility study needs at least one ground-motion record");
  for (const FragilityRecord& r : records) {
    if (r.ground.empty()) throw InvalidArgument("ground-motion record " + r.name + " has no samples");
    if (measure == IntensityMeasure::kPga && !(r.ground.PeakHorizontal() > 0.0)) {
      throw InvalidArgument("ground-motion record " + r.name + " has no horizontal acceleration to scale to a PGA");
    }
  }
  if (levels.empty()) throw InvalidArgument("give at least one intensity level");
  for (std::size_t i = 0; i < levels.size(); ++i) {
    if (!(levels[i] > 0.0) || !std::isfinite(levels[i])) {
      throw InvalidArgument(fmt::format("intensity levels must be positive numbers, got {}", levels[i]));
    }
    if (i > 0 && !(levels[i] > levels[i - 1])) {
      throw InvalidArgument(fmt::format("intensity levels must be increasing, got {} after {}", levels[i], levels[i - 1]));
    }
  }
  if (samples_per_level < 1) throw InvalidArgument("samples per level must be at least 1");
  if (angle_rad && !std::isfinite(*angle_rad)) throw InvalidArgument("the incidence angle must be finite");
  for (double f : tilt_fractions) {
    if (!(f > 0.0 && f < 1.0)) {
      throw InvalidArgument(fmt::format("tilt thresholds are fractions of the critical tilt in (0, 1), got {}", f));
    }
  }
  response.Validate();
  if (!response.simulation.sample_attitude) throw InvalidArgument("a fragility study needs the sampled attitude (tilts)");
}

std::int64_t FragilityStudyOptions::num_samples() const {
  return static_cast<std::int64_t>(blocks.size() * levels.size()) * samples_per_level;
}

std::string FragilityStudyOptions::SettingsText() const {
  std::string s = fmt::format("fragility v2; seed={}; measure={}; samples_per_level={}; angle={}; levels=", seed,
                              ToString(measure), samples_per_level,
                              angle_rad ? fmt::format("{:.17g}", *angle_rad) : std::string("uniform"));
  for (double l : levels) s += fmt::format("{:.17g},", l);
  s += "; tilts=";
  for (double f : tilt_fractions) s += fmt::format("{:.17g},", f);
  for (const FragilityBlock& b : blocks) {
    s += fmt::format("; block {}: b1={:.17g} b2={:.17g} h={:.17g} m={:.17g} lambda={:.17g}±{:.17g} "
                     "lambda_lat={:.17g}±{:.17g} lambda_lon={:.17g}±{:.17g} tau_edge={:.17g} facet_tau={}",
                     b.id, b.block.b1(), b.block.b2(), b.block.h(), b.block.mass(), b.lambda.mean, b.lambda.sd,
                     b.lambda_lat.mean, b.lambda_lat.sd, b.lambda_lon.mean, b.lambda_lon.sd, b.tau_edge,
                     core::ToString(b.facet_tau_rule));
  }
  for (const FragilityRecord& r : records) {
    s += fmt::format("; record {}: dt={:.17g} t0={:.17g} n={} hash={}", r.name, r.ground.dt_s(), r.ground.t_start_s(),
                     r.ground.size(), RecordHash(r.ground));
  }
  const core::SimulationOptions& o = response.simulation;
  s += fmt::format("; response: start={} tail={:.17g} end_at_rest={} rate={:.17g} gravity={:.17g} rel_tol={:.17g} "
                   "abs_tol={:.17g} event_tol={:.17g} max_step={:.17g} zeno_dt={:.17g} rest_height={:.17g} max_impacts={}",
                   core::ToString(response.start), response.tail_s,
                   response.end_at_rest, o.rate_hz, o.gravity_m_s2, o.rel_tol, o.abs_tol, o.event_time_tol_s,
                   o.max_step_s, o.zeno_dt_s, o.rest_energy_height_m, o.max_impacts);
  // Only when not the default, so that journals of studies under the default rule still resume.
  if (o.overturn != core::OverturnRule::kComOverSupport) s += fmt::format(" overturn={}", core::ToString(o.overturn));
  return s;
}

SampleInputs DrawSample(const FragilityStudyOptions& study, std::int64_t index) {
  if (index < 0 || index >= study.num_samples()) {
    throw InvalidArgument(fmt::format("sample index {} outside the study's 0…{}", index, study.num_samples() - 1));
  }
  SampleInputs in;
  in.index = index;
  const std::int64_t per_block = static_cast<std::int64_t>(study.levels.size()) * study.samples_per_level;
  in.block = static_cast<int>(index / per_block);
  in.level = static_cast<int>((index % per_block) / study.samples_per_level);
  const std::int64_t j = index % study.samples_per_level;
  in.record = static_cast<int>(j % static_cast<std::int64_t>(study.records.size()));
  in.intensity = study.levels[static_cast<std::size_t>(in.level)];
  in.seed = io::SplitMix64(io::SplitMix64(study.seed) + static_cast<std::uint64_t>(index));
  io::SynthRandom random(in.seed, io::SynthStream::kFragilitySample);
  const double u = random.Uniform();  // drawn even for a fixed angle, so the parameters never depend on it
  in.angle_rad = study.angle_rad ? *study.angle_rad : kTwoPi * (1.0 - u);  // [0, 2π)
  const FragilityBlock& b = study.blocks[static_cast<std::size_t>(in.block)];
  in.params.lambda = b.lambda.mean + b.lambda.sd * random.Normal();
  in.params.lambda_lat = b.lambda_lat.mean + b.lambda_lat.sd * random.Normal();
  in.params.lambda_lon = b.lambda_lon.mean + b.lambda_lon.sd * random.Normal();
  in.params.tau_edge = b.tau_edge;
  in.params.facet_tau_rule = b.facet_tau_rule;
  return in;
}

core::GroundMotion SampleGroundMotion(const FragilityStudyOptions& study, const SampleInputs& inputs, double* scale) {
  // Views of the record (GroundMotion::RotatedAndScaled): every thread shares the study's one copy of it.
  const core::GroundMotion& record = study.records[static_cast<std::size_t>(inputs.record)].ground;
  const double factor = study.measure == IntensityMeasure::kPga
                            ? inputs.intensity * core::kRecordGravity /
                                  record.RotatedAndScaled(inputs.angle_rad, 1.0).PeakHorizontal()
                            : inputs.intensity;
  if (scale) *scale = factor;
  return record.RotatedAndScaled(inputs.angle_rad, factor);
}

SampleOutcome RunSample(const FragilityStudyOptions& study, std::int64_t index) {
  const SampleInputs in = DrawSample(study, index);
  SampleOutcome o{};
  o.index = index;
  o.block = in.block;
  o.level = in.level;
  o.record = in.record;
  o.intensity = in.intensity;
  o.angle_rad = in.angle_rad;
  o.lambda = in.params.lambda;
  o.lambda_lat = in.params.lambda_lat;
  o.lambda_lon = in.params.lambda_lon;
  o.seed = in.seed;
  o.t_overturn_s = kNaN;
  const core::GroundMotion ground = SampleGroundMotion(study, in, &o.scale);
  o.pga_horizontal_m_s2 = ground.PeakHorizontal();
  const core::Block& block = study.blocks[static_cast<std::size_t>(in.block)].block;
  o.critical_tilt_rad = std::atan(std::min(block.b1(), block.b2()) / block.h());
  try {
    const core::Response r = core::Respond(block, in.params, ground, study.response);
    const core::ResponseSummary& s = r.summary;
    o.end_reason = static_cast<std::int32_t>(s.end_reason);
    o.t_end_s = s.t_end_s;
    if (s.t_overturn_s) o.t_overturn_s = *s.t_overturn_s;
    o.overturned = s.overturned ? 1 : 0;
    o.peak_tilt_rad = s.peak_tilt_rad;
    o.peak_rotation_rad = s.peak_rotation_rad;
    o.peak_rate_rad_s = s.peak_rate_rad_s;
    o.num_impacts = static_cast<std::int64_t>(s.num_impacts);
    o.max_discarded_rate_rad_s = s.max_discarded_rate_rad_s;
    o.counted = s.end_reason == core::EndReason::kRest || s.end_reason == core::EndReason::kTMax || s.overturned ? 1 : 0;
  } catch (const InvalidArgument&) {
    o.end_reason = kSampleInvalid;  // parameters Respond refuses (the distribution reached a non-finite value)
  }
  return o;
}

std::vector<SampleOutcome> RunSamples(const FragilityStudyOptions& study, const std::vector<std::int64_t>& indices,
                                      int threads) {
  std::vector<SampleOutcome> out(indices.size());
  fitting::ParallelFor(indices.size(), threads, [&](std::size_t i) { out[i] = RunSample(study, indices[i]); });
  return out;
}

FragilitySummary SummariseFragility(const FragilityStudyOptions& study, const std::vector<SampleOutcome>& outcomes) {
  const std::int64_t n = study.num_samples();
  if (static_cast<std::int64_t>(outcomes.size()) != n) {
    throw InvalidArgument(fmt::format("the study has {} samples, {} outcomes given", n, outcomes.size()));
  }
  for (std::int64_t i = 0; i < n; ++i) {
    if (outcomes[static_cast<std::size_t>(i)].index != i) {
      throw InvalidArgument(fmt::format("outcome {} has index {}: outcomes must be complete and sorted", i,
                                        outcomes[static_cast<std::size_t>(i)].index));
    }
  }
  FragilitySummary summary;
  summary.samples = n;
  std::vector<std::string> names{"overturning"};
  for (double f : study.tilt_fractions) names.push_back(TiltLimitStateName(f));
  const std::size_t states = names.size();
  std::size_t at = 0;
  for (const FragilityBlock& b : study.blocks) {
    FragilityBlockResult result;
    result.id = b.id;
    result.limit_states = names;
    std::vector<std::vector<LevelCount>> counts(states);
    for (double intensity : study.levels) {
      FragilityLevel level;
      level.intensity = intensity;
      level.samples = study.samples_per_level;
      std::vector<std::int64_t> exceeded(states, 0);
      for (std::int64_t j = 0; j < study.samples_per_level; ++j, ++at) {
        const SampleOutcome& o = outcomes[at];
        if (!o.counted) {
          ++level.not_counted;
          continue;
        }
        ++level.counted;
        if (o.overturned) ++exceeded[0];
        for (std::size_t t = 0; t < study.tilt_fractions.size(); ++t) {
          if (o.overturned || o.peak_tilt_rad >= study.tilt_fractions[t] * o.critical_tilt_rad) ++exceeded[1 + t];
        }
      }
      for (std::size_t s = 0; s < states; ++s) {
        LimitStateCount c;
        c.exceeded = exceeded[s];
        c.probability = level.counted > 0 ? static_cast<double>(c.exceeded) / static_cast<double>(level.counted) : kNaN;
        c.wilson_95 = WilsonInterval(c.exceeded, level.counted, kConfidence);
        c.clopper_pearson_95 = ClopperPearsonInterval(c.exceeded, level.counted, kConfidence);
        level.limit_states.push_back(c);
        counts[s].push_back({intensity, level.counted, c.exceeded});
      }
      summary.not_counted += level.not_counted;
      result.levels.push_back(std::move(level));
    }
    for (std::size_t s = 0; s < states; ++s) result.curves.push_back(FitLognormalFragility(counts[s]));
    summary.blocks.push_back(std::move(result));
  }
  return summary;
}

}  // namespace rockfit::quake
