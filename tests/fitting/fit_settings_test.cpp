// The settings hash changes exactly when something that changes a fit's result changes.
#include "rockfit/fitting/fit_settings.hpp"

#include <gtest/gtest.h>

namespace rockfit::fitting {
namespace {

TEST(FitSettings, TheHashIsStableAndFollowsEveryResultChangingSetting) {
  const ParameterSet p = ParameterSet::Defaults();
  const TrialFitOptions o;
  const std::string base = SettingsHash(FitSettingsJson(p, o));
  EXPECT_EQ(base, SettingsHash(FitSettingsJson(p, o)));
  EXPECT_EQ(base.size(), 16u);

  TrialFitOptions threads = o;
  threads.fit.num_threads = 7;  // the result does not depend on the number of threads
  EXPECT_EQ(base, SettingsHash(FitSettingsJson(p, threads)));

  TrialFitOptions method = o;
  method.fit.method = FitMethod::kCeres;
  EXPECT_NE(base, SettingsHash(FitSettingsJson(p, method)));
  TrialFitOptions seed = o;
  seed.fit.global.seed += 1;
  EXPECT_NE(base, SettingsHash(FitSettingsJson(p, seed)));
  TrialFitOptions t_end = o;
  t_end.t_end_s = 2.0;
  EXPECT_NE(base, SettingsHash(FitSettingsJson(p, t_end)));
  ParameterSet bounds = p;
  bounds[ParameterId::kLambdaLon].upper = 2.0;
  EXPECT_NE(base, SettingsHash(FitSettingsJson(bounds, o)));
  ParameterSet fixed = p;
  fixed[ParameterId::kLambdaLat].fixed = true;
  EXPECT_NE(base, SettingsHash(FitSettingsJson(fixed, o)));
  EXPECT_NE(base, SettingsHash(FitSettingsJson(p, o, R"({"files": "raw/T2"})")));
}

TEST(FitSettings, HashIsFnv1a64) {
  // Published FNV-1a 64 test vectors.
  EXPECT_EQ(SettingsHash(""), "cbf29ce484222325");
  EXPECT_EQ(SettingsHash("a"), "af63dc4c8601ec8c");
}

}  // namespace
}  // namespace rockfit::fitting
