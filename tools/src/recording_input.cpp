#include "recording_input.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/io/hdf5_file.hpp"

namespace rockfit::tools {

namespace {

bool HasExtension(const std::string& path, std::initializer_list<const char*> extensions) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return std::any_of(extensions.begin(), extensions.end(), [&](const char* e) { return ext == e; });
}

bool IsRockfitHdf5(const std::filesystem::path& path, const std::string& format) {
  if (format == "rockfit-hdf5") return true;
  if (format != "auto") return false;
  return HasExtension(path.string(), {".h5", ".hdf5"}) || io::hdf5::File::IsHdf5(path);
}

io::Recording LoadRecordingFile(const std::filesystem::path& path, const std::string& format,
                                const std::optional<double>& rate_hz, const std::string& mounting,
                                const std::string& rate_origin) {
  (void)rate_hz;
  (void)mounting;
  (void)rate_origin;
  throw BadInput(fmt::format("{} ({}): reading IMU files is not connected to this command yet; convert the "
                             "recording to rockfit's HDF5 first",
                             path.string(), format));
}

}  // namespace

void AddRecordingOptions(CLI::App& app, RecordingArgs& args) {
  app.add_option("PATH", args.path,
                 "Recording: an x-IMU GUI prefix or file, an x-IMU3 directory, a CSV file, rockfit's HDF5 file, or a "
                 "campaign manifest (.toml) with --trial")
      ->required();
  app.add_option("--trial", args.trial_id, "Trial id, when PATH is a manifest or an HDF5 file with several trials")
      ->group("Input");
  app.add_option("--format", args.format, "Input format: auto, ximu-gui, ximu3, generic-csv, rockfit-hdf5")
      ->capture_default_str()
      ->check(CLI::IsMember(io::ManifestFormats()))
      ->group("Input");
  app.add_option("--rate", args.rate_hz, "Sample rate [Hz] when the files do not state it")->group("Input");
  app.add_option("--mounting", args.mounting, "Sensor axes in the block frame, e.g. x,-y,-z (identity by default)")
      ->group("Input");
}

std::string TrialNameFrom(const std::string& text) {
  std::string name;
  for (char c : text) {
    name += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.' ? c : '_';
  }
  if (name.empty() || name == "." || name == "..") name = "trial";
  return name;
}

io::Recording LoadManifestTrial(const io::TrialSpec& trial) {
  if (IsRockfitHdf5(trial.files, trial.format)) return io::ReadRecordingHdf5(trial.files, "");
  return LoadRecordingFile(trial.files, trial.format, trial.rate_hz, trial.mounting, "manifest");
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
    if (args.format != "auto" || args.rate_hz || !args.mounting.empty()) {
      throw InvalidArgument("--format, --rate and --mounting come from the manifest when PATH is a manifest");
    }
    const io::TrialSpec& trial = manifest.FindTrial(args.trial_id);
    input.manifest_block = manifest.FindBlock(trial.block_id);
    input.recording = LoadManifestTrial(trial);
    input.trial_id = trial.id;
    input.labels = {trial.block_id, trial.position, trial.notes};
    return input;
  }
  if (IsRockfitHdf5(args.path, args.format)) {
    if (args.rate_hz || !args.mounting.empty()) {
      throw InvalidArgument("--rate and --mounting do not apply to rockfit's HDF5 files (they were applied when the "
                            "trial was stored)");
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
  input.recording = LoadRecordingFile(args.path, args.format, args.rate_hz, args.mounting, "option");
  input.trial_id = TrialNameFrom(std::filesystem::path(args.path).filename().string());
  return input;
}

}  // namespace rockfit::tools
