#include "rockfit/io/load_options.hpp"

#include <cmath>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"
#include "text/header_matching.hpp"

namespace rockfit::io {

std::string FormatName(RecordingFormat format) {
  switch (format) {
    case RecordingFormat::kAuto:
      return "auto";
    case RecordingFormat::kXimuGui:
      return "ximu-gui";
    case RecordingFormat::kXimu3:
      return "ximu3";
    case RecordingFormat::kGenericCsv:
      return "generic-csv";
    case RecordingFormat::kRockfitHdf5:
      return "rockfit-hdf5";
  }
  return "auto";
}

std::optional<RecordingFormat> ParseFormatName(std::string_view name) {
  const std::string text = NormalizeHeader(name);
  for (RecordingFormat format : {RecordingFormat::kAuto, RecordingFormat::kXimuGui, RecordingFormat::kXimu3,
                                 RecordingFormat::kGenericCsv, RecordingFormat::kRockfitHdf5}) {
    if (text == FormatName(format)) return format;
  }
  if (text == "csv") return RecordingFormat::kGenericCsv;
  return std::nullopt;
}

std::string OrientationChoiceName(OrientationChoice choice) {
  switch (choice) {
    case OrientationChoice::kAuto:
      return "auto";
    case OrientationChoice::kEulerAngles:
      return "euler";
    case OrientationChoice::kQuaternion:
      return "quaternion";
    case OrientationChoice::kRotationMatrix:
      return "matrix";
    case OrientationChoice::kNone:
      return "none";
  }
  return "auto";
}

std::optional<OrientationChoice> ParseOrientationChoice(std::string_view name) {
  const std::string text = NormalizeHeader(name);
  for (OrientationChoice choice : {OrientationChoice::kAuto, OrientationChoice::kEulerAngles,
                                   OrientationChoice::kQuaternion, OrientationChoice::kRotationMatrix,
                                   OrientationChoice::kNone}) {
    if (text == OrientationChoiceName(choice)) return choice;
  }
  return std::nullopt;
}

void LoadOptions::Validate() const {
  if (rate_hz && !(std::isfinite(*rate_hz) && *rate_hz > 0.0 && *rate_hz <= kMaxRate_hz)) {
    throw InvalidArgument(fmt::format("the sample rate must be a number of Hz in (0, {:g}], got {}", kMaxRate_hz, *rate_hz));
  }
  if (rate_origin != RateSource::kOption && rate_origin != RateSource::kManifest) {
    throw InvalidArgument(std::string("rate_origin must be \"option\" or \"manifest\", got \"") +
                          ToString(rate_origin) + "\"");
  }
  if (columns) columns->Validate();
}

}  // namespace rockfit::io
