#include "rockfit/app/recording_input.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

#include <fmt/format.h>

#include "rockfit/app/output_kind.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/io/hdf5_file.hpp"
#include "rockfit/io/load_recording.hpp"

namespace rockfit::app {

namespace {

bool HasExtension(const std::string& path, std::initializer_list<const char*> extensions) {
  const std::string ext = LowerCaseExtension(path);
  return std::any_of(extensions.begin(), extensions.end(), [&](const char* e) { return ext == e; });
}

bool IsRockfitHdf5(const std::filesystem::path& path, const std::string& format) {
  const auto parsed = io::ParseFormatName(format);
  if (parsed == io::RecordingFormat::kRockfitHdf5) return true;
  if (parsed != io::RecordingFormat::kAuto) return false;
  return HasExtension(path.string(), {".h5", ".hdf5"}) || io::hdf5::File::IsHdf5(path);
}

// --orientation as given on the command line; InvalidArgument for any other text.
io::OrientationChoice OrientationArgument(const std::string& orientation) {
  const auto parsed = io::ParseOrientationChoice(orientation);
  if (!parsed) {
    throw InvalidArgument("--orientation must be auto, euler, quaternion, matrix or none (none: the attitude is "
                          "integrated from the gyro), got '" + orientation + "'");
  }
  return *parsed;
}

io::LoadOptions MakeLoadOptions(const std::string& format, const std::optional<double>& rate_hz,
                                io::RateSource rate_origin, const std::string& mounting, const std::string& columns,
                                const std::string& orientation) {
  io::LoadOptions options;
  const auto parsed_format = io::ParseFormatName(format);
  if (!parsed_format) {
    throw InvalidArgument("--format must be auto, ximu-gui, ximu3, generic-csv (csv) or rockfit-hdf5, got '" + format + "'");
  }
  options.format = *parsed_format;
  options.rate_hz = rate_hz;
  options.rate_origin = rate_origin;
  if (!mounting.empty()) {
    const io::MountingOption option = io::MountingOption::Parse(mounting);
    options.mounting = option.given;
    options.estimate_mounting = option.estimate;
  }
  if (!columns.empty()) options.columns = io::ColumnMap::Parse(columns);
  options.orientation = OrientationArgument(orientation);
  options.Validate();
  return options;
}

}  // namespace


std::string TrialNameFrom(const std::string& text) {
  std::string name;
  for (char c : text) {
    name += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.' ? c : '_';
  }
  if (name.empty() || name == "." || name == "..") name = "trial";
  return name;
}

io::Recording LoadManifestTrial(const io::TrialSpec& trial, const std::string& orientation) {
  if (IsRockfitHdf5(trial.files, trial.format)) return io::ReadRecordingHdf5(trial.files, "");
  OrientationArgument(orientation);  // a bad command-line value is the caller's, not the manifest's
  io::LoadOptions options;
  try {
    options = MakeLoadOptions(trial.format, trial.rate_hz, io::RateSource::kManifest, trial.mounting, trial.columns,
                              orientation);
  } catch (const InvalidArgument& e) {  // a manifest entry is input data
    throw BadInput(fmt::format("trial '{}' (line {}): {}", trial.id, trial.where.line, e.what()));
  }
  return io::LoadRecording(trial.files, options);
}

TrialInput LoadTrialInput(const RecordingArgs& args) {
  TrialInput input;
  if (args.rate_hz && (!std::isfinite(*args.rate_hz) || *args.rate_hz <= 0.0)) {
    throw InvalidArgument("--rate must be a positive number of Hz");
  }
  if (HasExtension(args.path, {".toml"})) {
    const io::Manifest manifest = io::ReadManifest(args.path);
    if (args.trial_id.empty()) {
      std::string ids;
      for (const auto& t : manifest.trials) ids += (ids.empty() ? "" : ", ") + t.id;
      throw InvalidArgument(fmt::format("{} is a manifest: say which trial with --trial ID (one of: {})", args.path,
                                        ids.empty() ? "none" : ids));
    }
    if (args.format != "auto" || args.rate_hz || !args.mounting.empty() || !args.columns.empty()) {
      throw InvalidArgument("--format, --rate, --mounting and --columns come from the manifest when PATH is a manifest");
    }
    const io::TrialSpec& trial = manifest.FindTrial(args.trial_id);
    input.manifest_block = manifest.FindBlock(trial.block_id);
    input.recording = LoadManifestTrial(trial, args.orientation);
    input.trial_id = trial.id;
    input.labels = {trial.block_id, trial.position, trial.notes};
    return input;
  }
  if (IsRockfitHdf5(args.path, args.format)) {
    if (args.rate_hz || !args.mounting.empty() || !args.columns.empty()) {
      throw InvalidArgument("--rate, --mounting and --columns do not apply to rockfit's HDF5 files (they were "
                            "applied when the trial was stored)");
    }
    input.stored = io::ReadTrialHdf5(args.path, args.trial_id);
    input.recording = input.stored->recording;
    input.trial_id = input.stored->id;
    input.labels = input.stored->labels;
    return input;
  }
  if (!args.trial_id.empty()) {
    throw InvalidArgument("--trial selects a trial of a manifest or of an HDF5 file; " + args.path + " is neither");
  }
  input.recording = io::LoadRecording(
      args.path,
      MakeLoadOptions(args.format, args.rate_hz, io::RateSource::kOption, args.mounting, args.columns, args.orientation));
  input.trial_id = TrialNameFrom(std::filesystem::path(args.path).filename().string());
  return input;
}

}  // namespace rockfit::app
