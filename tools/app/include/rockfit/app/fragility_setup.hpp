// `fragility` for both front ends: the arguments of a Monte-Carlo fragility study (blocks and their parameter
// distributions, records, intensity levels, samples) as plain values, and the study they make
// (quake::FragilityStudyOptions). The program adds threads, MPI ranks and the journal; Python runs the samples on
// threads; both give the same outcomes for the same seed.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "rockfit/app/block_args.hpp"
#include "rockfit/quake/fragility_study.hpp"

namespace rockfit::app {

struct FragilityArgs {
  BlockArgs block;  // --block may list several ids (ID,ID,…) of one manifest
  std::string fits, group, position;
  double lambda = 1.0, lambda_lat = 0.0, lambda_lon = 1.0, tau_edge = 0.0;
  double lambda_sd = 0.0, lambda_lat_sd = 0.0, lambda_lon_sd = 0.0;
  std::string facet_tau = "no-spin";
  std::vector<std::string> records;
  std::string record_format = "auto";
  std::string units = "g";
  std::optional<double> csv_dt_s;
  int synthetic_records = 0;
  std::uint64_t synthetic_seed = 1;
  double synthetic_duration_s = 20.0;
  double synthetic_dt_s = 0.005;
  std::string pga, scale;   // levels: LIST or FROM:TO:N (exactly one of them)
  std::string angle = "random";  // [deg] or random
  std::string tilts;        // fractions of the critical tilt
  std::int64_t samples = 100;
  std::uint64_t seed = 1;
  double tail_s = 5.0;
  double rate_hz = 200.0;
  std::string overturn = "support";
};

// Throws InvalidArgument for bad arguments (naming the program's option), BadInput for unreadable records or fit
// files; checks the study against the limits of docs/file-formats.md ("Limits").
quake::FragilityStudyOptions MakeFragilityStudy(const FragilityArgs& args);

}  // namespace rockfit::app
