// Every enum that rockfit writes to a file or a JSON document reads back: ToString → FromString gives the value,
// through a JSON document (as `--json` prints it and Python reads it) and through an HDF5 string attribute (as the
// result files store it), and an unknown name is refused without touching the value.
#include <initializer_list>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "rockfit/core/facet_impact.hpp"
#include "rockfit/core/general_impact_map.hpp"
#include "rockfit/core/simulator.hpp"
#include "rockfit/fitting/fit_campaign.hpp"
#include "rockfit/fitting/fit_options.hpp"
#include "rockfit/fitting/fit_summary.hpp"
#include "rockfit/fitting/local_optimizer.hpp"
#include "rockfit/fitting/model_failure.hpp"
#include "rockfit/fitting/parameters.hpp"
#include "rockfit/fitting/uncertainty.hpp"
#include "rockfit/io/avrf.hpp"
#include "rockfit/io/drift_correction.hpp"
#include "rockfit/io/ground_motion_csv.hpp"
#include "rockfit/io/gyro_attitude.hpp"
#include "rockfit/io/hdf5_file.hpp"
#include "rockfit/io/load_options.hpp"
#include "rockfit/io/opmf.hpp"
#include "rockfit/io/recording.hpp"
#include "rockfit/io/trial_metrics.hpp"
#include "rockfit/io/units.hpp"
#include "rockfit/quake/fragility_study.hpp"
#include "rockfit/quake/lognormal_fragility.hpp"
#include "scratch_dir.hpp"

namespace rockfit {
namespace {

using testing::ScratchDir;

// Every value of `values` survives text, JSON and HDF5, and the names are distinct.
template <class Enum, class Parse, class Name>
void ExpectRoundTripsNamed(const char* enum_name, std::initializer_list<Enum> list, Parse parse, Name name_of) {
  const std::vector<Enum> values(list);
  const ScratchDir dir(std::string("enum_") + enum_name);
  io::hdf5::File file = io::hdf5::File::Create(dir / "enums.h5");
  const io::hdf5::Group root = file.Root();
  std::vector<std::string> names;
  for (std::size_t k = 0; k < values.size(); ++k) {
    const std::string name = name_of(values[k]);
    for (const std::string& other : names) EXPECT_NE(name, other) << enum_name << ": two values share a name";
    names.push_back(name);
    EXPECT_EQ(parse(name), values[k]) << enum_name << " '" << name << "' from text";
    const nlohmann::json document = nlohmann::json::parse(nlohmann::json{{"value", name}}.dump());
    EXPECT_EQ(parse(document.at("value").get<std::string>()), values[k]) << enum_name << " '" << name << "' from JSON";
    root.SetString("value_" + std::to_string(k), name);
  }
  file.Close();
  const io::hdf5::File read = io::hdf5::File::Open(dir / "enums.h5");
  for (std::size_t k = 0; k < values.size(); ++k) {
    const std::optional<std::string> stored = read.Root().GetString("value_" + std::to_string(k));
    ASSERT_TRUE(stored.has_value());
    EXPECT_EQ(parse(*stored), values[k]) << enum_name << " '" << *stored << "' from HDF5";
  }
}

template <class Enum, class Parse>
void ExpectRoundTrips(const char* enum_name, std::initializer_list<Enum> list, Parse parse) {
  ExpectRoundTripsNamed(enum_name, list, parse, [](Enum value) { return std::string(ToString(value)); });
}

// FromString as a function of the name; an unknown name fails and leaves the value alone.
template <class Enum>
auto ByFromString(Enum sentinel) {
  return [sentinel](const std::string& name) {
    Enum value = sentinel;
    EXPECT_TRUE(FromString(name, &value)) << name;
    Enum untouched = sentinel;
    EXPECT_FALSE(FromString(name + "?", &untouched));
    EXPECT_EQ(untouched, sentinel);
    return value;
  };
}

TEST(EnumNames, CoreEnumsRoundTripThroughTextJsonAndHdf5) {
  using namespace core;
  ExpectRoundTrips("FacetTauRule", {FacetTauRule::kNoSpin, FacetTauRule::kFixed}, ByFromString(FacetTauRule::kNoSpin));
  ExpectRoundTrips("StopCondition", {StopCondition::kPhase4, StopCondition::kRest, StopCondition::kOverturned,
                                     StopCondition::kTMax}, ByFromString(StopCondition::kPhase4));
  ExpectRoundTrips("OverturnRule", {OverturnRule::kComOverSupport, OverturnRule::kFallsOnSide},
                   ByFromString(OverturnRule::kComOverSupport));
  ExpectRoundTrips("ImpactKind", {ImpactKind::kFacet, ImpactKind::kEdge, ImpactKind::kZeno, ImpactKind::kRest,
                                  ImpactKind::kUplift}, ByFromString(ImpactKind::kFacet));
  ExpectRoundTrips("EndReason", {EndReason::kPhase4, EndReason::kRest, EndReason::kOverturned, EndReason::kTMax,
                                 EndReason::kFailed, EndReason::kLiftOff}, ByFromString(EndReason::kPhase4));
  ExpectRoundTrips("FailureReason", {FailureReason::kNone, FailureReason::kEdgeImpact, FailureReason::kFacetImpact,
                                     FailureReason::kIntegratorStep, FailureReason::kImpactCascade,
                                     FailureReason::kMaxImpacts, FailureReason::kEnergyBlowUp},
                   ByFromString(FailureReason::kNone));
  ExpectRoundTrips("ImpactStatus", {ImpactStatus::kOk, ImpactStatus::kInfeasible, ImpactStatus::kAmbiguous,
                                    ImpactStatus::kSingular}, ByFromString(ImpactStatus::kOk));
  ExpectRoundTrips("ModeKind", {ModeKind::kEdge, ModeKind::kVertex, ModeKind::kRest, ModeKind::kOverturned,
                                ModeKind::kFailed}, ByFromString(ModeKind::kEdge));
  ExpectRoundTrips("GroundStart", {GroundStart::kFlatAtRest, GroundStart::kAsOptions},
                   ByFromString(GroundStart::kFlatAtRest));
}

TEST(EnumNames, IoEnumsRoundTripThroughTextJsonAndHdf5) {
  using namespace io;
  ExpectRoundTrips("RateSource", {RateSource::kOption, RateSource::kManifest, RateSource::kRegisters,
                                  RateSource::kTimestamps, RateSource::kFile}, ByFromString(RateSource::kOption));
  ExpectRoundTrips("UpliftFormula", {UpliftFormula::kComUplift, UpliftFormula::kPaperPrinted},
                   ByFromString(UpliftFormula::kComUplift));
  ExpectRoundTrips("AnchorMethod", {AnchorMethod::kSubsample, AnchorMethod::kSample},
                   ByFromString(AnchorMethod::kSubsample));
  ExpectRoundTrips("AnchorSource", {AnchorSource::kOmegaY, AnchorSource::kOmegaX}, ByFromString(AnchorSource::kOmegaY));
  ExpectRoundTrips("AvrfStatus", {AvrfStatus::kOk, AvrfStatus::kNoImpact, AvrfStatus::kTooFewPeaks,
                                  AvrfStatus::kInvalidUplift, AvrfStatus::kNoBlock}, ByFromString(AvrfStatus::kOk));
  // The option values of the readers (--format, --orientation) have their own name pairs.
  ExpectRoundTripsNamed("RecordingFormat",
                        {RecordingFormat::kAuto, RecordingFormat::kXimuGui, RecordingFormat::kXimu3,
                         RecordingFormat::kGenericCsv, RecordingFormat::kRockfitHdf5},
                        [](const std::string& name) { return ParseFormatName(name).value(); },
                        [](RecordingFormat f) { return FormatName(f); });
  ExpectRoundTripsNamed("OrientationChoice",
                        {OrientationChoice::kAuto, OrientationChoice::kEulerAngles, OrientationChoice::kQuaternion,
                         OrientationChoice::kRotationMatrix, OrientationChoice::kNone},
                        [](const std::string& name) { return ParseOrientationChoice(name).value(); },
                        [](OrientationChoice c) { return OrientationChoiceName(c); });
  ExpectRoundTrips("MountingStatus", {MountingStatus::kOk, MountingStatus::kPartial, MountingStatus::kNoAccelerometer,
                                      MountingStatus::kNoRelease, MountingStatus::kNoRest, MountingStatus::kNotChecked},
                   ByFromString(MountingStatus::kOk));
  ExpectRoundTrips("MetricsStatus", {MetricsStatus::kOk, MetricsStatus::kNoImpact, MetricsStatus::kNoInPlaneMotion,
                                     MetricsStatus::kTooFewPeaks, MetricsStatus::kInvalidUplift, MetricsStatus::kNoBlock,
                                     MetricsStatus::kLoadError}, ByFromString(MetricsStatus::kOk));
  ExpectRoundTrips("OpmfStatus", {OpmfStatus::kOk, OpmfStatus::kNoImpact, OpmfStatus::kNoInPlaneMotion},
                   ByFromString(OpmfStatus::kOk));
  ExpectRoundTrips("AttitudeStart", {AttitudeStart::kAccelerometer, AttitudeStart::kLevel},
                   ByFromString(AttitudeStart::kAccelerometer));
  // Units: the canonical spelling (UnitName) is one of the spellings the column grammar reads.
  ExpectRoundTripsNamed("AngularRateUnit", {AngularRateUnit::kDegreesPerSecond, AngularRateUnit::kRadiansPerSecond},
                        [](const std::string& name) { return ParseAngularRateUnit(name).value(); },
                        [](AngularRateUnit u) { return UnitName(u); });
  ExpectRoundTripsNamed("AngleUnit", {AngleUnit::kDegrees, AngleUnit::kRadians},
                        [](const std::string& name) { return ParseAngleUnit(name).value(); },
                        [](AngleUnit u) { return UnitName(u); });
  ExpectRoundTripsNamed("AccelerationUnit", {AccelerationUnit::kG, AccelerationUnit::kMetresPerSecond2},
                        [](const std::string& name) { return ParseAccelerationUnit(name).value(); },
                        [](AccelerationUnit u) { return UnitName(u); });
  ExpectRoundTripsNamed("TimeUnit",
                        {TimeUnit::kSeconds, TimeUnit::kMilliseconds, TimeUnit::kMicroseconds, TimeUnit::kNanoseconds},
                        [](const std::string& name) { return ParseTimeUnit(name).value(); },
                        [](TimeUnit u) { return UnitName(u); });
  ExpectRoundTripsNamed("GroundAccelerationUnit",
                        {GroundAccelerationUnit::kG, GroundAccelerationUnit::kMetrePerSecond2,
                         GroundAccelerationUnit::kCentimetrePerSecond2},
                        [](const std::string& name) { return ParseGroundAccelerationUnit(name); },
                        [](GroundAccelerationUnit u) { return std::string(UnitName(u)); });
}

TEST(EnumNames, FittingAndQuakeEnumsRoundTripThroughTextJsonAndHdf5) {
  using namespace fitting;
  // FromString, and the option parsers built on it (they throw for an unknown name).
  ExpectRoundTrips("FitMethod", {FitMethod::kNelderMead, FitMethod::kCeres, FitMethod::kAuto},
                   ByFromString(FitMethod::kAuto));
  ExpectRoundTrips("FitMethod", {FitMethod::kNelderMead, FitMethod::kCeres, FitMethod::kAuto},
                   [](const std::string& name) { return ParseFitMethod(name); });
  ExpectRoundTrips("IntervalMethod", {IntervalMethod::kNone, IntervalMethod::kFast, IntervalMethod::kThorough},
                   ByFromString(IntervalMethod::kNone));
  ExpectRoundTrips("IntervalMethod", {IntervalMethod::kNone, IntervalMethod::kFast, IntervalMethod::kThorough},
                   [](const std::string& name) { return ParseIntervalMethod(name); });
  ExpectRoundTrips("BoundsSet", {BoundsSet::kEmpirical, BoundsSet::kTheoretical}, ByFromString(BoundsSet::kEmpirical));
  ExpectRoundTrips("BoundsSet", {BoundsSet::kEmpirical, BoundsSet::kTheoretical},
                   [](const std::string& name) { return ParseBoundsSet(name); });
  ExpectRoundTripsNamed("ParameterId",
                        {ParameterId::kT0, ParameterId::kAlpha, ParameterId::kLambda, ParameterId::kLambdaLat,
                         ParameterId::kLambdaLon, ParameterId::kTauEdge},
                        [](const std::string& name) { return ParseParameterName(name); },
                        [](ParameterId id) { return std::string(Name(id)); });
  ExpectRoundTrips("WarningKind",
                   {WarningKind::kAtBound, WarningKind::kNotIdentifiable, WarningKind::kSimulationFailures,
                    WarningKind::kNotConverged, WarningKind::kStdErrorUnavailable, WarningKind::kInfeasible,
                    WarningKind::kPoorFit, WarningKind::kSecondBasin, WarningKind::kNotDetermined,
                    WarningKind::kMovedByIntervals, WarningKind::kLateralMotionUnexplained,
                    WarningKind::kMovedByLateralRescan, WarningKind::kModelErrorDominates,
                    WarningKind::kWindowExtended, WarningKind::kReleaseTiltDisagrees,
                    WarningKind::kTurnedBeforeFall, WarningKind::kMovingAtRelease, WarningKind::kSensorTurnedAboutZ},
                   ByFromString(WarningKind::kAtBound));
  ExpectRoundTrips("TrialStatus", {TrialStatus::kFitted, TrialStatus::kSkipped, TrialStatus::kInfeasible,
                                   TrialStatus::kFailed}, ByFromString(TrialStatus::kFitted));
  ExpectRoundTrips("TerminationType", {TerminationType::kConvergence, TerminationType::kNoConvergence,
                                       TerminationType::kFailure, TerminationType::kNotASearch},
                   ByFromString(TerminationType::kConvergence));
  ExpectRoundTrips("ModelFailure",
                   {ModelFailure::kNone, ModelFailure::kNonFiniteParameter, ModelFailure::kT0OutsideWindow,
                    ModelFailure::kAllSamplesClipped,
                    ModelFailure::kInvalidParameters, ModelFailure::kSimulatorException, ModelFailure::kOverturned,
                    ModelFailure::kEdgeImpact, ModelFailure::kFacetImpact, ModelFailure::kIntegrator,
                    ModelFailure::kImpactCascade, ModelFailure::kTooManyImpacts, ModelFailure::kFailed,
                    ModelFailure::kIncompleteRun, ModelFailure::kWrongSampleCount, ModelFailure::kNonFiniteOutput,
                    ModelFailure::kInterrupted},
                   ByFromString(ModelFailure::kNone));
  ExpectRoundTrips("Determination", {Determination::kYes, Determination::kSignOnly, Determination::kNo},
                   ByFromString(Determination::kYes));
  ExpectRoundTrips("LognormalFitStatus",
                   {quake::LognormalFitStatus::kOk, quake::LognormalFitStatus::kNoExceedance,
                    quake::LognormalFitStatus::kAllExceeded, quake::LognormalFitStatus::kSeparated,
                    quake::LognormalFitStatus::kTooFewLevels, quake::LognormalFitStatus::kNotConverged},
                   ByFromString(quake::LognormalFitStatus::kOk));
  ExpectRoundTrips("IntensityMeasure", {quake::IntensityMeasure::kPga, quake::IntensityMeasure::kScale},
                   ByFromString(quake::IntensityMeasure::kPga));
}

}  // namespace
}  // namespace rockfit
