#include "rockfit/io/load_recording.hpp"

#include "rockfit/core/errors.hpp"
#include "rockfit/io/format_detection.hpp"
#include "rockfit/io/generic_csv_reader.hpp"
#include "rockfit/io/ximu3_reader.hpp"
#include "rockfit/io/ximu_gui_reader.hpp"

namespace rockfit::io {

Recording LoadRecording(const std::filesystem::path& path, const LoadOptions& options) {
  options.Validate();
  const DetectedSource source = DetectRecordingSource(path, options.format);
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
    case RecordingFormat::kRockfitHdf5:
      // Until the HDF5 store (issue 4 item 4) is connected here.
      throw BadInput(source.path.string() +
                     ": HDF5 recordings are read by rockfit's HDF5 store, which is not connected to LoadRecording in "
                     "this build. Read the original IMU files instead (x-IMU prefix, x-IMU3 directory or CSV).");
    case RecordingFormat::kAuto:
      break;
  }
  throw BadInput(path.string() + ": the recording format could not be determined");
}

}  // namespace rockfit::io
