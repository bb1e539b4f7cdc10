// Recording is a plain aggregate defined in its header; the readers fill it (load_recording.cpp). Here: the names
// of RateSource.
#include "rockfit/io/recording.hpp"

namespace rockfit::io {

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
