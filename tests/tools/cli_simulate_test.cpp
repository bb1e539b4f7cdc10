// `rockfit simulate` run as a real binary: the JSON keys of docs/file-formats.md §9, CSV, HDF5 (checked with h5py), exit codes.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cli_runner.hpp"
#include "rockfit/core/block.hpp"
#include "rockfit/core/planar_rocking.hpp"

namespace rockfit::testing {
namespace {

const std::string kB1 = "0.04999303"; // h·tan 0.245 for h = 0.2 m, rounded

std::vector<std::string> Fig14Args() {
  return {"simulate", "--b1", kB1, "--b2", "0.04", "--h", "0.2", "--density", "2692", "--alpha", "0.197",
          "--lambda", "2.185", "--lambda-lat", "-2.032", "--lambda-lon", "0.197"};
}

std::vector<std::string> With(std::vector<std::string> args, const std::vector<std::string>& more) {
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

struct TempDir {
  std::filesystem::path path;
  TempDir() {
    path = std::filesystem::temp_directory_path() / ("rockfit_cli_sim_" + std::to_string(::getpid()));
    std::filesystem::create_directories(path);
  }
  ~TempDir() { std::filesystem::remove_all(path); }
};

TEST(CliSimulate, Fig14CaseGivesTheDocumentedJsonKeys) {
  const CommandResult r = RunRockfit(Fig14Args());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  EXPECT_EQ(json["end_reason"], "phase4");
  EXPECT_GT(json["t_end"].get<double>(), 0.9);
  ASSERT_TRUE(json["impacts"].is_array());
  EXPECT_GE(json["impacts"].size(), 10u);
  for (const char* key : {"t", "kind", "contact_before", "contact_after", "omega_minus_B", "omega_plus_B",
                          "omega_minus_W", "omega_plus_W", "tau", "delta_energy", "status"}) {
    EXPECT_TRUE(json["impacts"][0].contains(key)) << key;
  }
  const auto& first = json["impacts"][0];
  EXPECT_EQ(first["kind"], "facet");
  EXPECT_EQ(first["contact_before"], "V1V2");
  // The first facet impact is at the quadrature time T(α) (docs/design.md §4).
  const core::Block block = core::Block::FromDensity(std::stod(kB1), 0.04, 0.2, 2692.0);
  EXPECT_NEAR(first["t"].get<double>(), core::FallTime(core::PlanarRockerAboutEdge(block, 1, 2), 0.197), 1e-9);
  const auto& samples = json["samples"];
  const std::size_t n = samples["t"].size();
  EXPECT_GT(n, 200u);
  EXPECT_EQ(samples["w_B"].size(), n);
  EXPECT_EQ(samples["w_B"][0].size(), 3u);
  EXPECT_EQ(samples["q_WB"].size(), n);
  EXPECT_EQ(samples["q_WB"][0].size(), 4u);
  EXPECT_EQ(samples["euler_zyx"].size(), n);
  EXPECT_EQ(samples["mode"][0], "V1V2");
  EXPECT_NEAR(samples["t"][1].get<double>(), 1.0 / 256.0, 1e-15);
  EXPECT_NEAR(samples["euler_zyx"][0][1].get<double>(), -0.197, 1e-12);
  EXPECT_TRUE(json["diagnostics"]["wall_time_s"].is_number());
  EXPECT_TRUE(json["diagnostics"]["segments"].is_array());
}

TEST(CliSimulate, CsvHasAHeaderWithUnitsAndOneRowPerSample) {
  const CommandResult r = RunRockfit(With(Fig14Args(), {"--format", "csv", "--rate", "100"}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream lines(r.out);
  std::string header;
  std::getline(lines, header);
  EXPECT_EQ(header, "t_s,w_x_B_rad_s,w_y_B_rad_s,w_z_B_rad_s,q_WB_w,q_WB_x,q_WB_y,q_WB_z,phi_z_rad,phi_y_rad,phi_x_rad,mode");
  std::size_t rows = 0;
  std::string line;
  std::string last;
  while (std::getline(lines, line)) {
    ++rows;
    last = line;
  }
  EXPECT_GT(rows, 90u);
  EXPECT_EQ(std::count(last.begin(), last.end(), ','), 11);
}

TEST(CliSimulate, Hdf5OpensInH5py) {
  if (std::system("/usr/bin/python3 -c 'import h5py' >/dev/null 2>&1") != 0) GTEST_SKIP() << "h5py not installed";
  const TempDir dir;
  const std::filesystem::path file = dir.path / "fig14.h5";
  const CommandResult r = RunRockfit(With(Fig14Args(), {"--format", "hdf5", "-o", file.string()}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string script =
      "import h5py, sys\n"
      "f = h5py.File(sys.argv[1], 'r')\n"
      "assert f.attrs['rockfit_schema_version'] == 2, f.attrs['rockfit_schema_version']\n"
      "w = f['samples/w_B_rad_s']\n"
      "assert w.shape[1] == 3 and w.shape[0] == f['samples/time_s'].shape[0]\n"
      "assert w.attrs['units'] in ('rad/s', b'rad/s')\n"
      "assert f['samples/q_WB'].shape[1] == 4\n"
      "kinds = [k.decode() if isinstance(k, bytes) else k for k in f['impacts/kind'][:]]\n"
      "assert kinds[0] == 'facet', kinds[0]\n"
      "reason = f['result'].attrs['end_reason']\n"
      "assert reason in ('phase4', b'phase4'), reason\n"
      "print('ok', w.shape[0], len(kinds))\n";
  const std::filesystem::path script_path = dir.path / "check.py";
  { std::ofstream(script_path) << script; }
  const std::string command = "/usr/bin/python3 " + ShellQuote(script_path.string()) + " " + ShellQuote(file.string()) +
                              " > " + ShellQuote((dir.path / "py.out").string()) + " 2>&1";
  const int status = std::system(command.c_str());
  EXPECT_EQ(status, 0) << ReadWholeFile(dir.path / "py.out");
  EXPECT_EQ(ReadWholeFile(dir.path / "py.out").rfind("ok", 0), 0u) << ReadWholeFile(dir.path / "py.out");
}

TEST(CliSimulate, Hdf5WithoutAnOutputFileIsAUsageError) {
  const CommandResult r = RunRockfit(With(Fig14Args(), {"--format", "hdf5"}));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("-o"), std::string::npos) << r.err;
}

TEST(CliSimulate, ReleaseEdgeMustBeTwoNeighbours) {
  CommandResult r = RunRockfit(With(Fig14Args(), {"--release-edge", "1,3"}));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("release edge"), std::string::npos) << r.err;
  r = RunRockfit(With(Fig14Args(), {"--release-edge", "one,two"}));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("--release-edge"), std::string::npos) << r.err;
}

TEST(CliSimulate, AFailedRunPrintsItsOutputAndExitsWithThree) {
  const CommandResult r = RunRockfit(With(Fig14Args(), {"--max-impacts", "3"}));
  EXPECT_EQ(r.exit_code, 3);
  const auto json = nlohmann::json::parse(r.out);
  EXPECT_EQ(json["end_reason"], "failed");
  EXPECT_NE(json["message"].get<std::string>().find("max_impacts"), std::string::npos);
  EXPECT_NE(r.err.find("failed"), std::string::npos) << r.err;
}

TEST(CliSimulate, UnwritableOutputExitsWithFour) {
  const CommandResult r = RunRockfit(With(Fig14Args(), {"-o", "/nonexistent-dir/out.json"}));
  EXPECT_EQ(r.exit_code, 4);
  EXPECT_NE(r.err.find("/nonexistent-dir/out.json"), std::string::npos) << r.err;
}

TEST(CliSimulate, HelpListsTheModelOptions) {
  const CommandResult r = RunRockfit({"simulate", "--help"});
  EXPECT_EQ(r.exit_code, 0);
  for (const char* option : {"--alpha", "--lambda", "--lambda-lat", "--lambda-lon", "--tau-edge", "--facet-tau",
                             "--release-edge", "--rate", "--stop", "--t-max", "--zeno-dt", "--format", "--output"}) {
    EXPECT_NE(r.out.find(option), std::string::npos) << option;
  }
}

}  // namespace
}  // namespace rockfit::testing
