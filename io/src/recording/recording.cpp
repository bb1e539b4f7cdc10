// Recording is a plain aggregate defined in its header; the readers fill it (load_recording.cpp). Here: the names
// of RateSource.
#include "rockfit/io/recording.hpp"
#include "rockfit/core/enum_names.hpp"

namespace rockfit::io {

const char* ToString(MountingStatus status) {
  switch (status) {
    case MountingStatus::kOk: return "ok";
    case MountingStatus::kPartial: return "partial";
    case MountingStatus::kNoAccelerometer: return "no_accelerometer";
    case MountingStatus::kNoRelease: return "no_release";
    case MountingStatus::kNoRest: return "no_rest";
    case MountingStatus::kNotChecked: return "not_checked";
  }
  return "not_checked";
}

bool FromString(std::string_view text, MountingStatus* status) {
  static constexpr MountingStatus kAll[] = {MountingStatus::kOk,        MountingStatus::kPartial,
                                            MountingStatus::kNoAccelerometer, MountingStatus::kNoRelease,
                                            MountingStatus::kNoRest,    MountingStatus::kNotChecked};
  return core::FromStringAmong(text, kAll, status);
}

const char* ToString(RateSource source) {
  switch (source) {
    case RateSource::kOption: return "option";
    case RateSource::kManifest: return "manifest";
    case RateSource::kRegisters: return "registers";
    case RateSource::kTimestamps: return "timestamps";
    case RateSource::kFile: return "file";
  }
  return "option";
}

bool FromString(std::string_view text, RateSource* source) {
  for (RateSource s : {RateSource::kOption, RateSource::kManifest, RateSource::kRegisters, RateSource::kTimestamps,
                       RateSource::kFile}) {
    if (text == ToString(s)) {
      *source = s;
      return true;
    }
  }
  return false;
}

}  // namespace rockfit::io
