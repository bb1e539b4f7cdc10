// `rockfit fragility` and `rockfit plot fragility` as the real binary: the table, --json and the HDF5 layout;
// the same datasets bit for bit with 1 thread, 2 threads and `mpirun -np 3`; kill -9 at random instants and
// --resume giving the uninterrupted result; a journal of another study refused; usage errors; and a build
// without MPI saying so under mpirun.
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <map>
#include <random>
#include <thread>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "build_type.hpp"
#include "cli_runner.hpp"
#include "process_control.hpp"
#include "rockfit/quake/fragility_study.hpp"
#include "rockfit/io/hdf5_file.hpp"
#include "rockfit/io/record_journal.hpp"
#include "scratch_dir.hpp"
#include "test_paths.hpp"

namespace rockfit::testing {
namespace {

// A small study: two generated records, three PGA levels, random incidence, spread in every parameter.
// In the Debug/sanitizer build (simulations ~150× slower) every study is cut to one sample per level of a 1.5 s
// record; the tests that need more run in optimised builds only.
int SamplesPerLevel(int samples) { return kOptimisedBuild ? samples : 1; }

std::vector<std::string> Study(const std::string& output, std::vector<std::string> more, int samples = 6,
                               double duration_s = 6.0) {
  samples = SamplesPerLevel(samples);
  if (!kOptimisedBuild) duration_s = std::min(duration_s, 1.5);
  std::vector<std::string> args{"fragility",     "--b1",         "0.05",        "--b2",
                                "0.04",          "--h",          "0.2",         "--density",
                                "2692",          "--lambda",     "0.9",         "--lambda-sd",
                                "0.05",          "--lambda-lat", "0.3",         "--lambda-lat-sd",
                                "0.1",           "--lambda-lon", "0.7",         "--lambda-lon-sd",
                                "0.05",          "--synthetic-records", "2",    "--synthetic-duration",
                                fmt::format("{}", duration_s), "--pga",  "0.25,0.45,0.7", "--samples",
                                std::to_string(samples), "--tilt", "0.5", "--seed", "11", "--tail", "1", "-o", output};
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

// Every dataset below `group` by path.
void CollectDatasets(const io::hdf5::Group& group, const std::string& prefix, std::vector<std::string>* out) {
  for (const std::string& name : group.Children()) {
    const std::string path = prefix.empty() ? name : prefix + "/" + name;
    if (group.IsGroup(name)) {
      CollectDatasets(group.OpenGroup(name), path, out);
    } else {
      out->push_back(path);
    }
  }
}

// The contents of every dataset of /fragility, as bytes (numbers as float64, strings joined).
std::map<std::string, std::string> FragilityDatasets(const std::filesystem::path& file_path) {
  const io::hdf5::File file = io::hdf5::File::Open(file_path);
  const io::hdf5::Group f = file.Root().OpenGroup("fragility");
  std::vector<std::string> names;
  CollectDatasets(f, "", &names);
  std::map<std::string, std::string> contents;
  for (const std::string& name : names) {
    std::string bytes;
    try {
      const std::vector<double> v = f.ReadDoubles(name);
      bytes.assign(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(double));
    } catch (const std::exception&) {
      for (const std::string& s : f.ReadStrings(name)) bytes += s + '\0';
    }
    contents[name] = bytes;
  }
  contents["@settings_hash"] = f.GetString("settings_hash").value_or("");
  return contents;
}

void ExpectSameDatasets(const std::map<std::string, std::string>& a, const std::map<std::string, std::string>& b,
                        const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (const auto& [name, bytes] : a) {
    const auto it = b.find(name);
    ASSERT_NE(it, b.end()) << what << ": " << name;
    EXPECT_TRUE(bytes == it->second) << what << ": dataset " << name << " differs";
  }
}

std::vector<std::string> Join(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

bool HaveMpirun() { return std::system("command -v mpirun >/dev/null 2>&1") == 0; }

TEST(CliFragility, TableJsonAndHdf5HoldTheDocumentedResults) {
  const ScratchDir dir("cli_fragility");
  const std::string h5 = (dir / "f.h5").string();
  const CommandResult table = RunRockfit(Study(h5, {"-j", "2"}, 4, 4.0));
  ASSERT_EQ(table.exit_code, 0) << table.err;
  for (const char* text : {"P(overturning) [95 % CP]", "P(tilt ≥ 0.5 θc)", "curve overturning", "simulations/s", "written"}) {
    EXPECT_NE(table.out.find(text), std::string::npos) << text << "\n" << table.out;
  }
  EXPECT_FALSE(std::filesystem::exists(h5 + ".journal")) << "the journal is removed once the file is written";
  const io::hdf5::File file = io::hdf5::File::Open(h5);
  const io::hdf5::Group f = file.Root().OpenGroup("fragility");
  EXPECT_EQ(f.ReadInts("samples/index").size(), static_cast<std::size_t>(3 * SamplesPerLevel(4)));
  for (const char* name : {"samples/lambda", "samples/angle_deg", "samples/end_reason", "samples/overturned",
                           "samples/peak_tilt_ratio", "records/name", "levels",
                           "blocks/block/limit_states/overturning/clopper_pearson_95_upper",
                           "blocks/block/limit_states/tilt_0.5/probability", "blocks/block/limit_states/overturning/curve/beta"}) {
    EXPECT_TRUE(f.Exists(name)) << name;
  }

  const CommandResult json = RunRockfit(Study((dir / "g.h5").string(), {"--json"}, 4, 4.0));
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const nlohmann::json j = nlohmann::json::parse(json.out);
  for (const char* key : {"output", "settings_hash", "samples", "simulated", "resumed", "not_counted", "ranks",
                          "threads_per_rank", "wall_s", "simulations_per_s", "intensity_measure", "blocks"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  const nlohmann::json& level = j["blocks"][0]["levels"][0];
  for (const char* key : {"intensity", "samples", "counted", "not_counted", "overturning", "tilt_0.5"}) {
    EXPECT_TRUE(level.contains(key)) << key;
  }
  EXPECT_TRUE(level["overturning"].contains("clopper_pearson_95"));
  EXPECT_TRUE(j["blocks"][0]["curves"]["overturning"].contains("status"));

  const std::string png = (dir / "f.png").string();
  const CommandResult plot = RunRockfit({"plot", "fragility", h5, "-o", png});
  if (plot.exit_code == 4 && plot.err.find("gnuplot") != std::string::npos) GTEST_SKIP() << "gnuplot not installed";
  ASSERT_EQ(plot.exit_code, 0) << plot.err;
  EXPECT_TRUE(std::filesystem::exists(png));
}

TEST(CliFragility, SeveralBlocksOfAManifestTakeTheirDistributionsFromTheBatchTable) {
  const ScratchDir dir("cli_fragility_blocks");
  dir.Write("m.toml",
            "[[blocks]]\nid = \"small\"\nb1 = 0.05\nb2 = 0.04\nh = 0.2\ndensity = 2692\n"
            "[[blocks]]\nid = \"large\"\nb1 = 0.15\nb2 = 0.12\nh = 0.6\ndensity = 2692\n");
  {
    // /summary/fits/per_group as `rockfit batch` writes it: λ pooled 0.9 with 95 % interval ±1.96·0.03 and a spread
    // of 0.04 between the trials (sd = 0.05); λ_lat not determined by any trial (mean −1.2, spread 0.2).
    io::hdf5::File file = io::hdf5::File::Create(dir / "fits.h5");
    const io::hdf5::Group g = file.Root().CreateGroup("summary/fits/per_group");
    g.WriteStrings("block", {"large", "small"});
    g.WriteStrings("position", {"A", "A"});
    g.WriteInts("n", {2, 3}, "1");
    const double nan = std::nan("");
    const auto parameter = [&](const std::string& name, double pooled, double half95, double mean, double spread) {
      g.WriteDoubles(name + "_pooled", {pooled, pooled}, "1");
      g.WriteDoubles(name + "_pooled_95_lower", {pooled - half95, pooled - half95}, "1");
      g.WriteDoubles(name + "_pooled_95_upper", {pooled + half95, pooled + half95}, "1");
      g.WriteDoubles(name + "_mean", {mean, mean}, "1");
      g.WriteDoubles(name + "_std", {spread, spread}, "1");
    };
    parameter("lambda", 0.9, 1.959963984540054 * 0.03, 0.91, 0.04);
    parameter("lambda_lat", nan, nan, -1.2, 0.2);
    parameter("lambda_lon", 0.7, 0.0, 0.7, 0.0);
    parameter("tau_edge", 0.0, 0.0, 0.0, 0.0);
    file.Close();
  }
  const std::string h5 = (dir / "f.h5").string();
  const CommandResult r = RunRockfit({"fragility", "--manifest", (dir / "m.toml").string(), "--block", "small,large",
                                      "--fits", (dir / "fits.h5").string(), "--position", "A", "--synthetic-records",
                                      "1", "--synthetic-duration", kOptimisedBuild ? "3" : "1.5", "--tail", "1", "--pga",
                                      "0.3,0.6", "--samples", "2", "-o", h5});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const io::hdf5::File file = io::hdf5::File::Open(h5);
  const io::hdf5::Group f = file.Root().OpenGroup("fragility");
  EXPECT_EQ(f.ReadStrings("blocks/id"), (std::vector<std::string>{"small", "large"}));
  for (const char* id : {"small", "large"}) {
    const std::vector<double> mean = f.ReadDoubles(std::string("blocks/") + id + "/parameters/mean");
    const std::vector<double> sd = f.ReadDoubles(std::string("blocks/") + id + "/parameters/sd");
    EXPECT_NEAR(mean[0], 0.9, 1e-12);
    EXPECT_NEAR(sd[0], 0.05, 1e-12) << "√(0.03² + 0.04²)";
    EXPECT_NEAR(mean[1], -1.2, 1e-12) << "the mean where no trial determined the parameter";
    EXPECT_NEAR(sd[1], 0.2, 1e-12);
    EXPECT_EQ(sd[2], 0.0);
  }
  EXPECT_EQ(f.ReadInts("samples/block"), (std::vector<std::int64_t>{0, 0, 0, 0, 1, 1, 1, 1}));
  // Explicit parameters and --fits do not mix; --fits needs the group.
  EXPECT_EQ(RunRockfit({"fragility", "--manifest", (dir / "m.toml").string(), "--block", "small", "--fits",
                        (dir / "fits.h5").string(), "--position", "A", "--lambda", "1", "--synthetic-records", "1",
                        "--pga", "0.3", "-o", h5}).exit_code, 1);
  const CommandResult missing = RunRockfit({"fragility", "--manifest", (dir / "m.toml").string(), "--block", "small",
                                            "--fits", (dir / "fits.h5").string(), "--position", "B",
                                            "--synthetic-records", "1", "--pga", "0.3", "-o", h5});
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("groups present: large,A; small,A"), std::string::npos) << missing.err;
}

TEST(CliFragility, OneThreadTwoThreadsAndThreeMpiRanksGiveIdenticalDatasets) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  const ScratchDir dir("cli_fragility_ranks");
  const std::string one = (dir / "one.h5").string(), two = (dir / "two.h5").string(), mpi = (dir / "mpi.h5").string();
  ASSERT_EQ(RunRockfit(Study(one, {"-j", "1"})).exit_code, 0);
  ASSERT_EQ(RunRockfit(Study(two, {"-j", "2", "--round", "5"})).exit_code, 0);
  const auto reference = FragilityDatasets(one);
  ExpectSameDatasets(reference, FragilityDatasets(two), "2 threads");
  if (!HaveMpirun()) GTEST_SKIP() << "mpirun not installed (apt-get install openmpi-bin)";
  std::string command = "mpirun --allow-run-as-root --oversubscribe -np 3 " + ShellQuote(RockfitBinary().string());
  for (const std::string& a : Study(mpi, {"-j", "1", "--round", "2"})) command += " " + ShellQuote(a);
  command += " >" + ShellQuote((dir / "mpi.out").string()) + " 2>&1";
  const int status = std::system(command.c_str());
  const std::string log = ReadWholeFile(dir / "mpi.out");
  if (log.find("built without MPI") != std::string::npos) GTEST_SKIP() << "this rockfit was built without MPI";
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << log;
  EXPECT_NE(log.find("on 3 rank(s)"), std::string::npos) << log;
  ExpectSameDatasets(reference, FragilityDatasets(mpi), "mpirun -np 3");
}

// The overturning PGA of a block without parameter spread under one record, by bisection with `rockfit respond`
// under overturning rule `rule`; `fragility` under the same rule then gives 0 just below it and 1 just above.
double ExpectFragilityStepAtTheOverturningPgaOfRespond(const std::string& rule) {
  // One record of the sample campaign at 30°, no parameter spread: bisection on --pga with `rockfit respond`.
  const std::string record = (SourceDir() / "data-samples" / "ground-motions" / "cp-seed2-0.45g.AT2").string();
  const std::vector<std::string> block{"--b1", "0.05000453", "--b2", "0.035", "--h", "0.2", "--density", "2692",
                                       "--lambda", "2.2", "--lambda-lat", "-1.9", "--lambda-lon", "0.22"};
  const auto overturns = [&](double pga_g) {
    std::vector<std::string> args{"respond", "--record", record, "--angle", "30", "--pga", fmt::format("{:.17g}", pga_g),
                                  "--overturn", rule};
    args.insert(args.end(), block.begin(), block.end());
    const CommandResult r = RunRockfit(args);  // the summary table (its JSON would carry every sample)
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("overturned      "), std::string::npos) << r.out;
    return r.out.find("overturned      yes") != std::string::npos;
  };
  double low = 0.1, high = 1.5;
  EXPECT_FALSE(overturns(low));
  EXPECT_TRUE(overturns(high));
  constexpr double kRelativeBracket = 1e-4;  // the bracket's width relative to the PGA
  while (high - low > kRelativeBracket * high) {
    const double mid = 0.5 * (low + high);
    (overturns(mid) ? high : low) = mid;
  }
  const ScratchDir dir("cli_fragility_extremes");
  std::vector<std::string> args{"fragility", "--record", record, "--angle", "30", "--pga",
                                fmt::format("{:.17g},{:.17g}", low, high), "--samples", "3", "--json",
                                "--overturn", rule, "-o", (dir / "f.h5").string()};
  args.insert(args.end(), block.begin(), block.end());
  const CommandResult r = RunRockfit(args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  if (r.exit_code != 0) return high;
  const nlohmann::json levels = nlohmann::json::parse(r.out)["blocks"][0]["levels"];
  EXPECT_EQ(levels[0]["counted"].get<int>(), 3);
  EXPECT_EQ(levels[0]["overturning"]["probability"].get<double>(), 0.0) << "PGA " << low;
  EXPECT_EQ(levels[1]["overturning"]["probability"].get<double>(), 1.0) << "PGA " << high;
  std::printf("overturning PGA of cp-seed2-0.45g.AT2 at 30°, rule %s: between %.6f and %.6f g\n", rule.c_str(), low,
              high);
  return high;
}

TEST(CliFragility, DeterministicBlockIsZeroBelowAndOneAboveTheOverturningPgaFoundWithRespond) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  const double support = ExpectFragilityStepAtTheOverturningPgaOfRespond("support");
  // Under the side rule the table may pull a block back from beyond the support: never a lower PGA.
  const double side = ExpectFragilityStepAtTheOverturningPgaOfRespond("side");
  EXPECT_GE(side, support * (1.0 - 2e-4));
}

TEST(CliFragility, KilledAtRandomInstantsAndResumedGivesTheUninterruptedResult) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  const ScratchDir reference_dir("cli_fragility_reference"), dir("cli_fragility_kill");
  const std::string reference = (reference_dir / "f.h5").string(), h5 = (dir / "f.h5").string();
  const std::vector<std::string> quiet{"-j", "1", "--round", "3"};
  constexpr int kSamples = 40;
  constexpr std::size_t kTotal = 3 * kSamples;
  const auto study = [&](const std::string& output, std::vector<std::string> more) {
    return Study(output, Join(quiet, more), kSamples, 20.0);
  };
  const auto [code, run_s] = RunRockfitTimed(study(reference, {}));
  ASSERT_EQ(code, 0);
  std::mt19937_64 rng(20261125);
  std::size_t journaled_before = 0;
  int killed = 0;
  bool finished = false;
  for (int k = 0; k < 4 && !finished; ++k) {
    const double instant_s = std::uniform_real_distribution<double>(0.05 * run_s, 0.45 * run_s)(rng);
    const pid_t pid = StartRockfit(study(h5, {"--resume"}));
    std::this_thread::sleep_for(std::chrono::duration<double>(instant_s));
    killed += ::kill(pid, SIGKILL) == 0 ? 1 : 0;
    WaitForExit(pid);
    const auto journal = io::ReadJournal(h5 + ".journal", "fragility", sizeof(quake::SampleOutcome), 1000000);
    finished = !journal && std::filesystem::exists(h5);
    const std::size_t now = journal ? journal->records.size() : finished ? kTotal : 0;
    EXPECT_GE(now, journaled_before) << "a kill lost journaled samples";
    journaled_before = std::max(journaled_before, now);
  }
  const CommandResult r = RunRockfit(study(h5, {"--resume", "--json"}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  if (!finished) {
    EXPECT_EQ(j["resumed"].get<std::size_t>(), journaled_before) << "every journaled sample is kept, none run twice";
    EXPECT_EQ(j["resumed"].get<std::size_t>() + j["simulated"].get<std::size_t>(), kTotal);
  }
  ExpectSameDatasets(FragilityDatasets(reference), FragilityDatasets(h5), "killed and resumed");
  std::printf("fragility: %d kills over a %.1f s study, %zu of %zu samples journaled before the last resume\n", killed,
              run_s, journaled_before, kTotal);
}

TEST(CliFragility, ResumeRefusesTheJournalOfAnotherStudy) {
  const ScratchDir dir("cli_fragility_other");
  const std::string h5 = (dir / "f.h5").string();
  { io::JournalWriter::Create(h5 + ".journal", "fragility", sizeof(quake::SampleOutcome), "0123456789abcdef"); }
  const CommandResult r = RunRockfit(Study(h5, {"--resume"}, 2, 3.0));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("other settings"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(h5));
  // Without --resume the study starts over, saying so.
  const CommandResult fresh = RunRockfit(Study(h5, {}, 2, 3.0));
  EXPECT_EQ(fresh.exit_code, 0) << fresh.err;
  EXPECT_NE(fresh.err.find("starting over"), std::string::npos) << fresh.err;
  // --resume of a finished study has nothing to do.
  const CommandResult again = RunRockfit(Study(h5, {"--resume"}, 2, 3.0));
  EXPECT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.out.find("nothing to do"), std::string::npos) << again.out;
}

TEST(CliFragility, BadOptionsAndRecordsExitWithTheirCodes) {
  const ScratchDir dir("cli_fragility_bad");
  const std::string h5 = (dir / "f.h5").string();
  std::vector<std::string> no_levels = Study(h5, {});
  const auto pga = std::find(no_levels.begin(), no_levels.end(), "--pga");
  no_levels.erase(pga, pga + 2);
  const CommandResult a = RunRockfit(no_levels);
  EXPECT_EQ(a.exit_code, 1);
  EXPECT_NE(a.err.find("--pga"), std::string::npos) << a.err;
  EXPECT_EQ(RunRockfit(Study(h5, {"--angle", "north"})).exit_code, 1);
  std::vector<std::string> falling_levels = Study(h5, {});
  *(std::find(falling_levels.begin(), falling_levels.end(), "--pga") + 1) = "0.5,0.3";
  const CommandResult falling = RunRockfit(falling_levels);
  EXPECT_EQ(falling.exit_code, 1);
  EXPECT_NE(falling.err.find("increasing"), std::string::npos) << falling.err;
  dir.Write("bad.AT2", "title\nno numbers here\n");
  const CommandResult bad = RunRockfit(Study(h5, {"--record", (dir / "bad.AT2").string()}));
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
  EXPECT_NE(bad.err.find("bad.AT2"), std::string::npos) << bad.err;
}

TEST(CliFragility, BuildWithoutMpiSaysSoWhenAskedOrStartedByMpirun) {
#ifdef ROCKFIT_TEST_WITH_MPI
  GTEST_SKIP() << "this build has MPI (the check is for builds with -DROCKFIT_WITH_MPI=OFF)";
#else
  const ScratchDir dir("cli_fragility_nompi");
  const CommandResult flag = RunRockfit(Study((dir / "f.h5").string(), {"--mpi"}, 1, 2.0));
  EXPECT_EQ(flag.exit_code, 1);
  EXPECT_NE(flag.err.find("built without MPI"), std::string::npos) << flag.err;
  std::string command = "OMPI_COMM_WORLD_SIZE=3 " + ShellQuote(RockfitBinary().string());
  for (const std::string& a : Study((dir / "f.h5").string(), {}, 1, 2.0)) command += " " + ShellQuote(a);
  command += " >/dev/null 2>" + ShellQuote((dir / "err").string());
  const int status = std::system(command.c_str());
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 1);
  const std::string err = ReadWholeFile(dir / "err");
  EXPECT_NE(err.find("3 copies"), std::string::npos) << err;
  EXPECT_FALSE(std::filesystem::exists(dir / "f.h5"));
#endif
}

}  // namespace
}  // namespace rockfit::testing
