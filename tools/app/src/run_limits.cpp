#include "rockfit/app/run_limits.hpp"

#include <cmath>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/quake/fragility_study.hpp"
#include "rockfit/io/input_limits.hpp"

namespace rockfit::app {

std::string LimitsHelp() {
  const auto mib = [](std::uint64_t bytes) { return bytes >> 20; };
  return fmt::format(
      "Limits (docs/file-formats.md, \"Limits\"): inputs must be regular files (a directory, FIFO, socket or device "
      "is refused);\n"
      "-o writes a regular file (a symbolic link is followed) and refuses a device, FIFO or socket.\n"
      "  recording CSV file     up to {} MiB (memory: about 6 times the file)\n"
      "  ground-motion record   up to {} MiB and {} samples per component (32 bytes each in memory)\n"
      "  manifest               up to {} MiB and {} [[blocks]] or [[trials]], dotted keys of up to {} parts\n"
      "  simulated motion       up to {:.0f} samples: (record + --tail), --t-max or --duration times --rate\n"
      "                         (about 150 bytes each in memory, more as JSON or CSV)\n"
      "  fragility study        up to {} levels, {} samples ({} bytes each), {} records with {} samples in all\n"
      "                         (24 bytes each, shared by the threads)",
      mib(io::kMaxRecordingFileBytes), mib(io::kMaxRecordFileBytes), io::kMaxRecordSamples,
      mib(io::kMaxManifestFileBytes), io::kMaxManifestEntries, io::kMaxManifestKeyParts, kMaxTrajectorySamples,
      kMaxFragilityLevels, kMaxFragilitySamples, sizeof(quake::SampleOutcome), kMaxFragilityRecords,
      kMaxStudyRecordSamples);
}

void RequireTrajectorySamplesWithinLimit(double seconds, double rate_hz, const std::string& options) {
  const double samples = seconds * rate_hz;
  if (std::isfinite(samples) && samples <= kMaxTrajectorySamples) return;
  if (!(seconds > 0.0) || !(rate_hz > 0.0)) return;  // refused where they are used, with their own message
  throw InvalidArgument(fmt::format("{} ask for {:.0f} samples ({} s at {} Hz), more than the {:.0f} a simulated "
                                    "motion may have (docs/file-formats.md, \"Limits\"); lower them",
                                    options, samples, seconds, rate_hz, kMaxTrajectorySamples));
}

void RequireResponseWithinLimit(const core::GroundMotion& ground, const std::string& source, bool from_file,
                                double tail_s, double rate_hz) {
  if (!(tail_s >= 0.0) || !std::isfinite(tail_s)) {
    throw InvalidArgument(fmt::format("--tail must be a finite number of seconds ≥ 0, got {}", tail_s));
  }
  if (!(rate_hz > 0.0) || !std::isfinite(rate_hz)) {
    throw InvalidArgument(fmt::format("--rate must be a positive number of hertz, got {}", rate_hz));
  }
  const double record_samples = ground.t_end_s() * rate_hz;
  if (!(record_samples <= kMaxTrajectorySamples) && !from_file) {
    throw InvalidArgument(fmt::format("the generated record of {:.6g} s at --rate {} Hz asks for {:.0f} response "
                                      "samples, more than the {:.0f} a response may have (docs/file-formats.md, "
                                      "\"Limits\"); lower --synthetic-duration or --rate",
                                      ground.t_end_s(), rate_hz, record_samples, kMaxTrajectorySamples));
  }
  if (!(record_samples <= kMaxTrajectorySamples)) {
    throw BadInput(fmt::format("{}: the record lasts {:.6g} s ({} samples at DT = {:.6g} s); its response at --rate "
                               "{} Hz would hold {:.3g} samples, more than the {:.0f} a response may have "
                               "(docs/file-formats.md, \"Limits\"): check DT (and --dt), cut the record or lower "
                               "--rate",
                               source, ground.t_end_s(), ground.size(), ground.dt_s(), rate_hz, record_samples,
                               kMaxTrajectorySamples));
  }
  const double samples = (ground.t_end_s() + tail_s) * rate_hz;
  if (!(samples <= kMaxTrajectorySamples)) {
    throw InvalidArgument(fmt::format("the record ({:.6g} s) and --tail {} s at --rate {} Hz ask for {:.0f} response "
                                      "samples, more than the {:.0f} a response may have (docs/file-formats.md, "
                                      "\"Limits\"); lower --tail or --rate",
                                      ground.t_end_s(), tail_s, rate_hz, samples, kMaxTrajectorySamples));
  }
}

}  // namespace rockfit::app
