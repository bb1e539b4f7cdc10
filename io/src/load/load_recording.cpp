#include "rockfit/io/load_recording.hpp"

#include <cmath>
#include <string>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/io/campaign_hdf5.hpp"
#include "load/format_detection.hpp"
#include "generic/generic_csv_reader.hpp"
#include "rockfit/io/mounting_estimate.hpp"
#include "ximu3/ximu3_reader.hpp"
#include "ximu/ximu_gui_reader.hpp"

namespace rockfit::io {

namespace {

// Reads `source` (detected from `path` and options.format).
Recording ReadRecording(const std::filesystem::path& path, const DetectedSource& source, const LoadOptions& options) {
  if (options.columns && source.format != RecordingFormat::kGenericCsv) {
    throw InvalidArgument("a column map applies to generic CSV files, but '" + path.string() + "' is read as " +
                          FormatName(source.format) + "; add --format csv to read that file as a generic CSV");
  }
  switch (source.format) {
    case RecordingFormat::kXimuGui:
      return ReadXimuGuiRecording(XimuGuiFileSet::Find(source.path), options);
    case RecordingFormat::kXimu3:
      return ReadXimu3Recording(source.path, options);
    case RecordingFormat::kGenericCsv:
      return ReadGenericCsvRecording(source.path, options);
    case RecordingFormat::kRockfitHdf5: {
      // rockfit's own store (campaign_hdf5.hpp): the file must hold one trial (use ReadRecordingHdf5 with an id
      // for files with several). Its samples are already in block axes and SI units.
      if (!options.mounting.is_identity() || options.estimate_mounting) {
        throw InvalidArgument(source.path.string() + ": a mounting applies when reading IMU files; the trials of a "
                              "rockfit HDF5 file are stored in block axes already");
      }
      Recording recording = ReadRecordingHdf5(source.path, "");
      if (options.rate_hz && std::abs(*options.rate_hz - recording.rate_hz) > 1e-9 * recording.rate_hz) {
        throw BadInput(source.path.string() + ": stored at " + std::to_string(recording.rate_hz) +
                       " Hz, but the rate given is " + std::to_string(*options.rate_hz) + " Hz; leave the rate out");
      }
      return recording;
    }
    case RecordingFormat::kAuto:
      break;
  }
  throw BadInput(path.string() + ": the recording format could not be determined");
}

}  // namespace

Recording LoadRecording(const std::filesystem::path& path, const LoadOptions& options) {
  options.Validate();
  const DetectedSource source = DetectRecordingSource(path, options.format);
  Recording recording = ReadRecording(path, source, options);
  if (source.format == RecordingFormat::kRockfitHdf5) return recording;  // stored in block axes

  const MountingEstimate estimate = EstimateMounting(recording);
  MountingCheck check = estimate.check;
  check.given = options.mounting.text();
  if (!options.estimate_mounting) {
    if (check.has_estimate()) {
      check.warning = MountingWarning(check, CorrectedMounting(options.mounting, estimate));
      if (!check.warning.empty()) recording.warnings.push_back(check.warning);
    }
    recording.mounting_check = check;
    return recording;
  }
  if (!check.has_estimate()) {
    throw BadInput(fmt::format("{}: --mounting auto cannot estimate the mounting: {}; give it instead (--mounting "
                               "x,-y,-z or w,x,y,z, or mounting = \"…\" in the manifest)",
                               recording.source, check.message));
  }
  LoadOptions corrected = options;
  corrected.mounting = CorrectedMounting(options.mounting, estimate);
  corrected.estimate_mounting = false;
  Recording result = ReadRecording(path, source, corrected);
  check.estimated = true;
  if (check.status == MountingStatus::kPartial) {
    check.warning = "mounting estimate: " + check.message;
    result.warnings.push_back(check.warning);
  }
  result.mounting_check = check;
  return result;
}

}  // namespace rockfit::io
