// `rockfit respond`, `rockfit ground-motion` and `rockfit plot response` run as the real binary: summary, JSON keys,
// HDF5 round trip through the plot, exit codes for bad records and missing fits.
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "build_type.hpp"
#include "cli_runner.hpp"
#include "rockfit/core/response.hpp"
#include "rockfit/io/hdf5_file.hpp"
#include "scratch_dir.hpp"
#include "test_paths.hpp"

namespace rockfit::testing {
namespace {

std::vector<std::string> Block() { return {"--b1", "0.05", "--b2", "0.04", "--h", "0.2", "--density", "2692"}; }

std::vector<std::string> Respond(std::vector<std::string> more) {
  std::vector<std::string> args{"respond"};
  for (const auto& a : Block()) args.push_back(a);
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

TEST(CliRespond, SyntheticRecordGivesASummaryAndJsonWithDocumentedKeys) {
  const CommandResult table = RunRockfit(Respond({"--synthetic", "4", "--pga", "0.4", "--lambda", "0.9", "--lambda-lat",
                                                 "0.3", "--lambda-lon", "0.8"}));
  ASSERT_EQ(table.exit_code, 0) << table.err;
  for (const char* row : {"status", "overturned", "peak tilt", "uplifts", "impacts", "friction ratio"}) {
    EXPECT_NE(table.out.find(row), std::string::npos) << row << "\n" << table.out;
  }
  const CommandResult json = RunRockfit(Respond({"--synthetic", "4", "--pga", "0.4", "--json"}));
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const nlohmann::json j = nlohmann::json::parse(json.out);
  for (const char* key : {"summary", "block", "parameters", "ground_motion", "impacts", "samples"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  for (const char* key : {"end_reason", "overturned", "t_overturn", "peak_tilt_rad", "peak_rotation_rad", "num_impacts",
                          "uplift_times", "max_friction_ratio"}) {
    EXPECT_TRUE(j["summary"].contains(key)) << key;
  }
  EXPECT_NEAR(j["ground_motion"]["pga_horizontal_m_s2"].get<double>(), 0.4 * 9.80665, 1e-9);
  EXPECT_EQ(j["samples"]["t"].size(), j["samples"]["a_g_W"].size());
}

// Runs that once ended as `failed` in a census of fragility samples of the sample campaign's blocks with their
// fitted spreads: each must end with a status (rest, t_max, overturned, lift_off).
TEST(CliRespond, RunsThatOnceFailedInAFragilityCensusEndWithAStatus) {
  const std::vector<std::string> block2{"--b1", "0.05000453", "--b2", "0.035", "--h", "0.2", "--mass", "7.538"};
  const std::vector<std::string> block3{"--b1", "0.05000453", "--b2", "0.045", "--h", "0.2", "--density", "2692"};
  const auto expect_status = [&](const std::vector<std::string>& block, std::vector<std::string> args,
                                 const std::string& what) {
    args.insert(args.begin(), "respond");
    args.insert(args.end(), block.begin(), block.end());
    args.push_back("--json");
    const CommandResult r = RunRockfit(args);
    ASSERT_EQ(r.exit_code, 0) << what << ": " << r.err;
    const nlohmann::json summary = nlohmann::json::parse(r.out)["summary"];
    EXPECT_NE(summary["end_reason"].get<std::string>(), "failed") << what << ": " << summary["message"];
    EXPECT_GE(summary["max_discarded_rate_rad_s"].get<double>(), 0.0) << what;
  };
  // A vertex lifted at 1e-6 m/s by a chatter's facet impact hopped for ~1e-7 s inside a 5 ms step; the event
  // search took its landing for the step's start, and the facet impact that followed had no solution.
  expect_status(block2,
                {"--lambda", "2.1771509303727963", "--lambda-lat", "-1.900754009726313", "--lambda-lon",
                 "0.2277491938384034", "--synthetic", "1", "--synthetic-duration", "20", "--scale", "2.471372835497835",
                 "--angle", "146.69969784969646"},
                "a hop shorter than the step");
  // The table drove the flat block right at its threshold: edge impacts around the base every ~5e-12 s at
  // 1e-11 rad/s ("more than 16 impacts at one instant"), a micro-chatter the contact now settles.
  const std::string record = (SourceDir() / "data-samples" / "ground-motions" / "cp-seed1-0.30g.AT2").string();
  expect_status(block3,
                {"--record", record, "--scale", "1.318181818181818", "--angle", "162.30398617869147", "--lambda",
                 "1.2393593972199581", "--lambda-lat", "4.2398603250082525", "--lambda-lon", "1.0821387835895908"},
                "a micro-chatter");
  const std::filesystem::path dir = GroundMotionsDir();
  if (dir.empty()) GTEST_SKIP() << "the real PEER records beside the checkout are not present";
  // An end vertex of edge V4V1 lifted and landed at the same instant, over and over ("more than 16 impacts at
  // t = 2.01662 s without the contact resolving").
  expect_status(block2,
                {"--lambda", "2.1501764880796337", "--lambda-lat", "-1.923644236599688", "--lambda-lon",
                 "0.2821196657186537", "--record", (dir / "elCentro.AT2").string(), "--scale", "1.5682830437237314",
                 "--angle", "54.58982266694947"},
                "an end that came straight back");
  // A 3D micro-chatter at 3e-9 rad/s (facet, vertex, edge impacts, Zeno, again) ran into max_impacts.
  expect_status(block3,
                {"--record", (dir / "A-ELC180.AT2").string(), "--scale", "6.360255643136818", "--angle",
                 "261.66070223715604", "--lambda", "1.3088067972533384", "--lambda-lat", "3.0137969826411766",
                 "--lambda-lon", "0.9284971749954252"},
                "a 3D micro-chatter");
}

TEST(CliRespond, FacetTauWrittenToJsonIsAcceptedBackByRespondSimulateAndFragility) {
  const CommandResult written = RunRockfit(Respond({"--synthetic", "4", "--pga", "0.3", "--facet-tau", "zero", "--json"}));
  ASSERT_EQ(written.exit_code, 0) << written.err;
  const std::string name = nlohmann::json::parse(written.out)["parameters"]["facet_tau"].get<std::string>();
  EXPECT_EQ(name, "fixed");
  const CommandResult again = RunRockfit(Respond({"--synthetic", "4", "--pga", "0.3", "--facet-tau", name, "--json"}));
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(nlohmann::json::parse(again.out)["summary"]["num_impacts"], nlohmann::json::parse(written.out)["summary"]["num_impacts"]);
  std::vector<std::string> simulate{"simulate", "--alpha", "0.1", "--lambda-lat", "0.3", "--facet-tau", name, "--json"};
  for (const auto& a : Block()) simulate.push_back(a);
  EXPECT_EQ(RunRockfit(simulate).exit_code, 0);
  const ScratchDir dir("cli_respond_facet_tau");
  std::vector<std::string> fragility{"fragility", "--synthetic-records", "1", "--synthetic-duration", "2", "--pga", "0.2",
                                     "--samples", "1", "--facet-tau", name, "-o", (dir / "f.h5").string()};
  for (const auto& a : Block()) fragility.push_back(a);
  EXPECT_EQ(RunRockfit(fragility).exit_code, 0);
}

TEST(CliRespond, OverturnSideCarriesTheMotionPastTheSupportUntilTheBlockLiesOnASide) {
  // A strong record overturns the block under both rules; under `side` later, with the block's z axis horizontal.
  const auto run = [](const char* rule) {
    const CommandResult r = RunRockfit(Respond({"--synthetic", "4", "--pga", "0.8", "--overturn", rule, "--json"}));
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return nlohmann::json::parse(r.out)["summary"];
  };
  const nlohmann::json support = run("support");
  const nlohmann::json side = run("side");
  ASSERT_TRUE(support["overturned"].get<bool>());
  ASSERT_TRUE(side["overturned"].get<bool>());
  EXPECT_EQ(support["overturn_rule"], "support");
  EXPECT_EQ(side["overturn_rule"], "side");
  EXPECT_GT(side["t_overturn"].get<double>(), support["t_overturn"].get<double>());
  EXPECT_NEAR(side["peak_tilt_rad"].get<double>(), M_PI / 2.0, 1e-9);
  EXPECT_LT(support["peak_tilt_rad"].get<double>(), 0.3);  // near the critical tilt
  const CommandResult bad = RunRockfit(Respond({"--synthetic", "4", "--overturn", "sideways"}));
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("--overturn"), std::string::npos) << bad.err;
}

// Near the overturning boundary a block that chatters along an edge turns round-off into either verdict
// (core/README.md, "Sensitivity of a single response"). The block of the response benchmark under this
// generated record is such a case: the 21 runs of --round-off disagree, and the table says so.
TEST(CliRespond, RoundOffReportsAVerdictThatDependsOnRoundOff) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  const std::vector<std::string> args{"respond", "--b1", "0.05000453", "--b2", "0.035", "--h", "0.2", "--density",
                                      "2692", "--lambda", "0.6", "--lambda-lat", "0.3", "--lambda-lon", "0.7",
                                      "--synthetic", "3", "--pga", "0.35", "--synthetic-duration", "30", "--angle", "30",
                                      "--round-off", "21"};
  const CommandResult table = RunRockfit(args);
  ASSERT_EQ(table.exit_code, 0) << table.err;
  EXPECT_NE(table.out.find("the verdict depends on round-off"), std::string::npos) << table.out;
  std::vector<std::string> json_args = args;
  json_args.push_back("--json");
  const CommandResult json = RunRockfit(json_args);
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const nlohmann::json spread = nlohmann::json::parse(json.out)["round_off"];
  EXPECT_EQ(spread["runs"].get<int>(), 21);
  EXPECT_GT(spread["overturned"].get<int>(), 0);
  EXPECT_LT(spread["overturned"].get<int>(), 21);
  EXPECT_EQ(spread["failed"].get<int>(), 0);
  EXPECT_LT(spread["peak_tilt_min_rad"].get<double>(), 0.05);  // some runs barely rock
  std::printf("round-off: %d of 21 runs overturn; peak tilt %.5f … %.5f rad\n", spread["overturned"].get<int>(),
              spread["peak_tilt_min_rad"].get<double>(), spread["peak_tilt_max_rad"].get<double>());
  const CommandResult bad = RunRockfit(Respond({"--synthetic", "4", "--round-off", "-1"}));
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("--round-off"), std::string::npos) << bad.err;
}

// tools/overturning_spectrum.py drives `rockfit respond` with a one-sine pulse written as CSV. Its smallest
// overturning amplitude must be what the same scan finds with rockfit::core::Respond in-process, whose curve the
// core tests check against a planar integration and a closed form: the script's pulse, units and parameters are
// the ones it states.
TEST(OverturningSpectrumScript, AgreesWithTheSameScanRunOnRespond) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  if (std::system("command -v python3 >/dev/null 2>&1") != 0) GTEST_SKIP() << "python3 is not available";
  const ScratchDir dir("overturning_spectrum");
  const std::string out = (dir.path() / "out.txt").string();
  const std::string command = "python3 " + ShellQuote((SourceDir() / "tools" / "overturning_spectrum.py").string()) +
                              " --rockfit " + ShellQuote(RockfitBinary().string()) +
                              " --alpha 0.25 --ratios 3 --step 0.05 --overturn side >" + ShellQuote(out) + " 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << ReadWholeFile(out);
  std::istringstream lines(ReadWholeFile(out));
  double ratio = 0.0, script = 0.0;
  for (std::string line; std::getline(lines, line);) {
    if (!line.empty() && line[0] != '#') std::istringstream(line) >> ratio >> script;
  }
  ASSERT_EQ(ratio, 3.0) << ReadWholeFile(out);

  // The same block, pulse and scan (from 1 in steps of 0.05, then bisection to 1e-3) on Respond.
  constexpr double kG = 9.81, kAlpha = 0.25, kTol = 1e-3;
  const core::Block block = core::Block::FromDensity(std::sin(kAlpha), std::sin(kAlpha), std::cos(kAlpha), 2500);
  const double p = std::sqrt(3.0 * kG / 4.0);
  const double omega = 3.0 * p;
  const double dt = 2.0 * M_PI / omega / 400.0;
  std::vector<double> pulse(401);
  for (std::size_t k = 0; k < pulse.size(); ++k) pulse[k] = std::sin(omega * static_cast<double>(k) * dt);
  core::ModelParameters params;
  params.lambda = 1.0;
  params.lambda_lat = 0.0;
  params.lambda_lon = 1.0;
  const auto overturns = [&](double amplitude_ratio) {
    std::vector<Eigen::Vector3d> a(pulse.size(), Eigen::Vector3d::Zero());
    for (std::size_t k = 0; k < pulse.size(); ++k) a[k].x() = amplitude_ratio * kG * std::tan(kAlpha) * pulse[k];
    core::ResponseOptions options;
    options.simulation.rate_hz = 10.0;
    options.simulation.overturn = core::OverturnRule::kFallsOnSide;
    options.tail_s = 8.0 / p;
    return core::Respond(block, params, core::GroundMotion::Uniform(dt, a), options).summary.overturned;
  };
  double lo = 1.0, hi = 1.0;
  while (!overturns(hi) && hi < 20.0) {
    lo = hi;
    hi += 0.05;
  }
  while (hi - lo > kTol) {
    const double mid = 0.5 * (lo + hi);
    (overturns(mid) ? hi : lo) = mid;
  }
  std::printf("one-sine pulse, θ_c = 0.25, ω_p/p = 3, falls on a side: script %.4f, Respond %.4f\n", script, hi);
  EXPECT_NEAR(script, hi, 2.0 * kTol);
}

TEST(CliRespond, Hdf5OutputFeedsPlotResponse) {
  ScratchDir dir("cli_respond");
  const std::string h5 = (dir.path() / "r.h5").string();
  const CommandResult r = RunRockfit(Respond({"--synthetic", "2", "--pga", "0.35", "--format", "hdf5", "-o", h5}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string png = (dir.path() / "r.png").string();
  const CommandResult plot = RunRockfit({"plot", "response", h5, "-o", png});
  if (plot.exit_code == 4 && plot.err.find("gnuplot") != std::string::npos) GTEST_SKIP() << "gnuplot not installed";
  ASSERT_EQ(plot.exit_code, 0) << plot.err;
  EXPECT_TRUE(std::filesystem::exists(png));
}

// A response file of schema version 1 (names without units, root attribute `schema_version`) still plots.
TEST(CliRespond, PlotResponseReadsAFileOfSchemaVersionOne) {
  ScratchDir dir("cli_respond");
  const std::string h5 = (dir.path() / "v1.h5").string();
  {
    const io::hdf5::File file = io::hdf5::File::Create(h5);
    const io::hdf5::Group root = file.Root();
    root.SetString("schema", "rockfit.simulation");
    root.SetInt("schema_version", 1);
    const std::vector<double> t = {0.0, 0.01, 0.02};
    const std::vector<Eigen::Vector3d> xyz(3, Eigen::Vector3d(0.1, 0.0, 0.0));
    const io::hdf5::Group samples = root.CreateGroup("samples");
    samples.WriteDoubles("t", t, "s");
    samples.WriteVectors("a_g_W", xyz, "m/s^2");
    samples.WriteDoubles("tilt", {0.0, 0.001, 0.0}, "rad");
    samples.WriteVectors("w_B", xyz, "rad/s");
    const io::hdf5::Group ground = root.CreateGroup("ground_motion");
    ground.WriteDoubles("t", t, "s");
    ground.WriteVectors("a_W", xyz, "m/s^2");
    const io::hdf5::Group impacts = root.CreateGroup("impacts");
    impacts.WriteDoubles("t", {0.01}, "s");
    impacts.WriteStrings("kind", {"uplift"});
    root.CreateGroup("result").SetString("end_reason", "rest");
    root.CreateGroup("response").SetDouble("critical_tilt_rad", 0.245);
  }
  const std::string png = (dir.path() / "v1.png").string();
  const CommandResult plot = RunRockfit({"plot", "response", h5, "-o", png});
  if (plot.exit_code == 4 && plot.err.find("gnuplot") != std::string::npos) GTEST_SKIP() << "gnuplot not installed";
  ASSERT_EQ(plot.exit_code, 0) << plot.err;
  EXPECT_NE(plot.out.find("written"), std::string::npos) << plot.out;
}

TEST(CliRespond, BadRecordIsExitTwoWithFileAndLine) {
  ScratchDir dir("cli_respond");
  const std::filesystem::path bad = dir.path() / "short.AT2";
  std::ofstream(bad) << "a\nb\nc\nNPTS=  5, DT= .01000 SEC\n  .1E-01  .2E-01\n";
  const CommandResult r = RunRockfit(Respond({"--record", bad.string()}));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("short.AT2:5"), std::string::npos) << r.err;
  const CommandResult missing = RunRockfit(Respond({"--record", bad.string(), "--fits", (dir.path() / "none.h5").string(),
                                                    "--trial", "x"}));
  EXPECT_EQ(missing.exit_code, 2) << missing.err;
  EXPECT_EQ(RunRockfit(Respond({})).exit_code, 1);
}

TEST(CliRespond, GroundMotionSynthWritesAnAt2FileThatInspectReads) {
  ScratchDir dir("cli_respond");
  const std::string at2 = (dir.path() / "gen.AT2").string();
  const CommandResult w = RunRockfit({"ground-motion", "synth", "--seed", "9", "--pga", "0.2", "--duration", "5", "-o", at2});
  ASSERT_EQ(w.exit_code, 0) << w.err;
  const CommandResult i = RunRockfit({"ground-motion", "inspect", at2, "--json"});
  ASSERT_EQ(i.exit_code, 0) << i.err;
  const nlohmann::json j = nlohmann::json::parse(i.out);
  EXPECT_EQ(j["records"][0]["npts"].get<int>(), 1001);
  EXPECT_NEAR(j["records"][0]["pga_g"].get<double>(), 0.2, 1e-7);
}

TEST(CliRespond, RealRecordsRespondAtAnIncidenceAngle) {
  const std::filesystem::path dir = GroundMotionsDir();
  if (dir.empty()) GTEST_SKIP() << "the real ground-motion records beside the checkout are not present";
  const CommandResult r = RunRockfit(Respond({"--record", (dir / "ARL360.at2").string(), "--angle", "30", "--json"}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["ground_motion"]["npts"].get<int>(), 2000);
  EXPECT_NEAR(j["ground_motion"]["pga_horizontal_m_s2"].get<double>() / 9.80665, 0.3081, 1e-4);
}

}  // namespace
}  // namespace rockfit::testing
