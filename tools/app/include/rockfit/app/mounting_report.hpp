// How the commands show the mounting of a recording and what the data say about it (io/mounting_estimate.hpp):
// one JSON object, one text line, the warning on stderr.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "rockfit/io/recording.hpp"

namespace rockfit::app {

// {"applied", "given", "estimated", "status", "message", "angles_deg" [x, y, z], "std_error_deg" [x, y, z],
//  "determined" [x, y, z], "disagreement_deg", "release_tilt_rad", "release_tilt_std_error_rad",
//  "turn_before_fall_deg", "warning"}; missing numbers are null.
nlohmann::json MountingJson(const io::Recording& recording);

// "auto → 0.99966,… (data − given about block x +0.01°, y −0.02°, z +3.00°, ±0.01°)" and similar.
std::string MountingText(const io::Recording& recording);

// Prints "rockfit: warning: …" on stderr when the data disagree with the mounting or leave an angle open.
void PrintMountingWarning(const io::Recording& recording);

}  // namespace rockfit::app
