#include "rockfit/app/fragility_setup.hpp"

#include <cmath>

#include <fmt/format.h>

#include "rockfit/app/fitted_parameters.hpp"
#include "rockfit/app/ground_motion_args.hpp"
#include "rockfit/app/option_grammar.hpp"
#include "rockfit/app/run_limits.hpp"
#include "rockfit/core/errors.hpp"

namespace rockfit::app {
namespace {


double ParseNumber(const std::string& cell, const std::string& option) {
  const std::optional<double> v = ParseFinite(cell);
  if (!v) throw InvalidArgument(fmt::format("{}: '{}' is not a number", option, cell));
  return *v;
}

// "0.1,0.2,0.4" or "FROM:TO:N" (N evenly spaced levels from FROM to TO).
std::vector<double> ParseLevels(const std::string& text, const std::string& option) {
  std::vector<double> levels;
  if (text.find(':') != std::string::npos) {
    const std::vector<std::string> parts = SplitList(text, ':');
    const double n = parts.size() == 3 ? ParseNumber(parts[2], option) : 0.0;
    if (parts.size() != 3 || n < 2 || n != std::floor(n)) {
      throw InvalidArgument(fmt::format("{} expects FROM:TO:N with N ≥ 2 levels, got '{}'", option, text));
    }
    if (n > static_cast<double>(kMaxFragilityLevels)) {
      throw InvalidArgument(fmt::format("{} asks for {} levels, more than the {} a study may have (docs/file-formats.md, "
                                        "\"Limits\"); a fragility curve needs a dozen", option, n, kMaxFragilityLevels));
    }
    const double from = ParseNumber(parts[0], option), to = ParseNumber(parts[1], option);
    for (int i = 0; i < static_cast<int>(n); ++i) levels.push_back(from + (to - from) * i / (n - 1.0));
    return levels;
  }
  for (const std::string& cell : SplitList(text)) levels.push_back(ParseNumber(cell, option));
  if (levels.size() > kMaxFragilityLevels) {
    throw InvalidArgument(fmt::format("{} lists {} levels, more than the {} a study may have (docs/file-formats.md, "
                                      "\"Limits\")", option, levels.size(), kMaxFragilityLevels));
  }
  return levels;
}

std::vector<quake::FragilityBlock> MakeBlocks(const FragilityArgs& cmd) {
  std::vector<std::string> ids = cmd.block.block_id.empty() ? std::vector<std::string>{""} : SplitList(cmd.block.block_id);
  std::string group_block, group_position = cmd.position;
  if (!cmd.group.empty()) {
    const std::size_t comma = cmd.group.find(',');
    if (comma == std::string::npos) throw InvalidArgument("--group expects BLOCK,POSITION such as block2,A");
    group_block = cmd.group.substr(0, comma);
    group_position = cmd.group.substr(comma + 1);
    if (ids.size() > 1) throw InvalidArgument("--group names one block; for several blocks give --position POSITION");
    if (cmd.block.block_id.empty() && !cmd.block.manifest_path.empty()) ids = {group_block};
  }
  if (!cmd.fits.empty() && group_position.empty()) {
    throw InvalidArgument("with --fits give --group BLOCK,POSITION (one block) or --position POSITION (the blocks of --block)");
  }
  if (cmd.fits.empty() && (!cmd.group.empty() || !cmd.position.empty())) {
    throw InvalidArgument("--group and --position need --fits FILE (the HDF5 file of rockfit batch)");
  }
  std::vector<quake::FragilityBlock> blocks;
  for (const std::string& id : ids) {
    BlockArgs args = cmd.block;
    args.block_id = id;
    quake::FragilityBlock b;
    b.id = id.empty() ? "block" : id;
    b.block = MakeBlock(args);
    b.facet_tau_rule = ParseFacetTauRule(cmd.facet_tau);
    if (!cmd.fits.empty()) {
      const std::string fit_block = group_block.empty() ? b.id : group_block;
      const FittedGroupRanges r = ReadFittedGroupRanges(cmd.fits, fit_block, group_position);
      b.lambda = {r.lambda.value, r.lambda.TotalSd()};
      b.lambda_lat = {r.lambda_lat.value, r.lambda_lat.TotalSd()};
      b.lambda_lon = {r.lambda_lon.value, r.lambda_lon.TotalSd()};
      b.tau_edge = r.tau_edge.value;
      b.source = r.description + " in " + cmd.fits + " (sd: estimate and between-trial spread)";
    } else {
      b.lambda = {cmd.lambda, cmd.lambda_sd};
      b.lambda_lat = {cmd.lambda_lat, cmd.lambda_lat_sd};
      b.lambda_lon = {cmd.lambda_lon, cmd.lambda_lon_sd};
      b.tau_edge = cmd.tau_edge;
      b.source = "command line";
    }
    blocks.push_back(b);
  }
  return blocks;
}

// Refuses a study whose records would hold more than kMaxStudyRecordSamples samples, before the next `adding`.
void RequireRecordSamplesWithinLimit(std::size_t held, double adding, const std::string& what) {
  if (static_cast<double>(held) + adding > static_cast<double>(kMaxStudyRecordSamples)) {
    throw InvalidArgument(fmt::format("{} would bring the study's records to {:.4g} samples, more than the {} a study "
                                      "may hold (docs/file-formats.md, \"Limits\"); use fewer or shorter records",
                                      what, static_cast<double>(held) + adding, kMaxStudyRecordSamples));
  }
}

std::vector<quake::FragilityRecord> LoadRecords(const FragilityArgs& cmd) {
  if (cmd.synthetic_records < 0) throw InvalidArgument("--synthetic-records must be ≥ 0");
  if (cmd.records.size() + static_cast<std::size_t>(cmd.synthetic_records) > kMaxFragilityRecords) {
    throw InvalidArgument(fmt::format("{} --record and --synthetic-records {} are more than the {} records a study may "
                                      "have (docs/file-formats.md, \"Limits\")",
                                      cmd.records.size(), cmd.synthetic_records, kMaxFragilityRecords));
  }
  std::vector<quake::FragilityRecord> records;
  std::size_t held = 0;  // samples of the records read so far
  for (const std::string& path : cmd.records) {
    GroundMotionArgs a;
    a.record = path;
    a.record_format = cmd.record_format;
    a.units = cmd.units;
    a.csv_dt_s = cmd.csv_dt_s;
    records.push_back({path, LoadGroundMotion(a).assembled.ground});
    RequireResponseWithinLimit(records.back().ground, path, true, cmd.tail_s, cmd.rate_hz);
    RequireRecordSamplesWithinLimit(held, static_cast<double>(records.back().ground.size()), "--record " + path);
    held += records.back().ground.size();
  }
  if (cmd.synthetic_records > 0) {
    const double each = cmd.synthetic_duration_s / cmd.synthetic_dt_s + 1.0;
    RequireRecordSamplesWithinLimit(held, static_cast<double>(cmd.synthetic_records) * each,
                                    fmt::format("--synthetic-records {} of {} s at {} s", cmd.synthetic_records,
                                                cmd.synthetic_duration_s, cmd.synthetic_dt_s));
  }
  for (int k = 0; k < cmd.synthetic_records; ++k) {
    GroundMotionArgs a;
    a.synthetic_seed = cmd.synthetic_seed + static_cast<std::uint64_t>(k);
    a.synthetic_duration_s = cmd.synthetic_duration_s;
    a.synthetic_dt_s = cmd.synthetic_dt_s;
    records.push_back({fmt::format("synthetic:{}", *a.synthetic_seed), LoadGroundMotion(a).assembled.ground});
    RequireResponseWithinLimit(records.back().ground, records.back().name, false, cmd.tail_s, cmd.rate_hz);
  }
  if (records.empty()) {
    throw InvalidArgument("give ground motions: --record FILE (repeatable; PEER AT2 or CSV) and/or --synthetic-records N");
  }
  return records;
}

}  // namespace

quake::FragilityStudyOptions MakeFragilityStudy(const FragilityArgs& cmd) {
  if (cmd.samples < 1) throw InvalidArgument("--samples must be at least 1");
  quake::FragilityStudyOptions study;
  study.blocks = MakeBlocks(cmd);
  study.records = LoadRecords(cmd);
  if (cmd.pga.empty() == cmd.scale.empty()) {
    throw InvalidArgument("give the intensity levels with exactly one of --pga LIST (g) or --scale LIST (factors)");
  }
  study.measure = cmd.pga.empty() ? quake::IntensityMeasure::kScale : quake::IntensityMeasure::kPga;
  study.levels = cmd.pga.empty() ? ParseLevels(cmd.scale, "--scale") : ParseLevels(cmd.pga, "--pga");
  study.samples_per_level = cmd.samples;
  const double samples = static_cast<double>(study.blocks.size()) * static_cast<double>(study.levels.size()) *
                         static_cast<double>(cmd.samples);
  if (samples > static_cast<double>(kMaxFragilitySamples)) {
    throw InvalidArgument(fmt::format("{} block(s) × {} levels × --samples {} are {:.4g} samples, more than the {} a "
                                      "study may have (docs/file-formats.md, \"Limits\"); lower --samples or the "
                                      "number of levels", study.blocks.size(), study.levels.size(), cmd.samples,
                                      samples, kMaxFragilitySamples));
  }
  if (cmd.angle != "random") study.angle_rad = ParseNumber(cmd.angle, "--angle") * M_PI / 180.0;
  if (!cmd.tilts.empty()) {
    for (const std::string& cell : SplitList(cmd.tilts)) study.tilt_fractions.push_back(ParseNumber(cell, "--tilt"));
  }
  study.seed = cmd.seed;
  study.response.tail_s = cmd.tail_s;
  study.response.simulation.rate_hz = cmd.rate_hz;
  study.response.simulation.overturn = ParseOverturnRule(cmd.overturn);
  study.Validate();
  return study;
}


}  // namespace rockfit::app
