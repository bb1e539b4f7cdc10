// The recording a command works on (`correct`, `metrics`, `plot euler`): a recording path in any format the
// readers know, a trial of rockfit's HDF5 file, or a trial of a campaign manifest — with the format, rate and
// mounting options of the readers.
#pragma once

#include <optional>
#include <string>


#include "rockfit/io/campaign_hdf5.hpp"
#include "rockfit/io/manifest.hpp"
#include "rockfit/io/recording.hpp"

namespace rockfit::app {

// Help text of --mounting (inspect, metrics, correct, fit, plot euler).
inline constexpr const char* kMountingHelp =
    "Sensor axes on the block: a permutation with signs 'x,-y,-z' (entry i = sensor axis along block axis i), a "
    "unit quaternion 'w,x,y,z' (q_BS), or 'auto' / 'auto:SPEC' to estimate the mounting from the recording (rest "
    "before the release, phase 1, rest after the rocking) starting at SPEC. Default: identity, checked against the "
    "data (a warning beyond 1°)";

struct RecordingArgs {
  std::string path;
  std::string trial_id;  // --trial: a trial of a manifest (PATH.toml) or of a rockfit HDF5 file
  std::string format = "auto";
  std::optional<double> rate_hz;
  std::string mounting;
  std::string columns;              // generic CSV column map (io/column_map.hpp)
  std::string orientation = "auto";  // attitude files: auto, euler, quaternion, matrix
};
// PATH (positional, required) and --trial, --format, --rate, --mounting, --columns, --orientation.

struct TrialInput {
  io::Recording recording;
  std::string trial_id;  // --trial, or a name made from the file name
  io::TrialLabels labels;
  std::optional<io::BlockSpec> manifest_block;  // PATH was a manifest
  std::optional<io::StoredTrial> stored;        // PATH was rockfit's HDF5 (holds the stored correction)
};

// BadInput (file, line, column, what to do) for unreadable data; InvalidArgument for options that do not fit.
TrialInput LoadTrialInput(const RecordingArgs& args);

// The recording of a manifest trial (its files, format, rate, mounting). `orientation` (auto, euler, quaternion,
// matrix, none) is the program's --orientation: the manifest has no such key, so the command line's choice holds for
// a manifest trial as for a path.
io::Recording LoadManifestTrial(const io::TrialSpec& trial, const std::string& orientation = "auto");

// A name usable as an HDF5 group: letters, digits, '-', '_', '.'; others become '_'.
std::string TrialNameFrom(const std::string& text);

}  // namespace rockfit::app
