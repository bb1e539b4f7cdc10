#include "rockfit/io/load_options.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"

namespace rockfit::io {
namespace {

TEST(LoadOptions, DefaultsAreValid) { EXPECT_NO_THROW(LoadOptions().Validate()); }

TEST(LoadOptions, RefusesRatesThatAreNotAPositiveNumberOfHertz) {
  for (double rate : {0.0, -256.0, std::nan(""), HUGE_VAL, 1e9}) {
    LoadOptions options;
    options.rate_hz = rate;
    EXPECT_THROW(options.Validate(), InvalidArgument) << rate;
  }
  LoadOptions options;
  options.rate_origin = RateSource::kRegisters;  // a rate found in the files, not given
  EXPECT_THROW(options.Validate(), InvalidArgument);
}

TEST(LoadOptions, FormatAndOrientationNamesRoundTrip) {
  for (auto format : {RecordingFormat::kAuto, RecordingFormat::kXimuGui, RecordingFormat::kXimu3,
                      RecordingFormat::kGenericCsv, RecordingFormat::kRockfitHdf5}) {
    EXPECT_EQ(ParseFormatName(FormatName(format)), format);
  }
  EXPECT_EQ(ParseFormatName("CSV"), RecordingFormat::kGenericCsv);
  EXPECT_FALSE(ParseFormatName("bin"));
  for (auto choice : {OrientationChoice::kAuto, OrientationChoice::kEulerAngles, OrientationChoice::kQuaternion,
                      OrientationChoice::kRotationMatrix, OrientationChoice::kNone}) {
    EXPECT_EQ(ParseOrientationChoice(OrientationChoiceName(choice)), choice);
  }
  EXPECT_FALSE(ParseOrientationChoice("gyro"));
}

}  // namespace
}  // namespace rockfit::io
