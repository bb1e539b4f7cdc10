#include "rockfit/io/csv_export.hpp"

#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "rocking_signals.hpp"
#include "scratch_dir.hpp"

namespace rockfit::io {
namespace {

std::vector<std::vector<std::string>> ReadCsv(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) cells.push_back(cell);
    if (!line.empty() && line.back() == ',') cells.emplace_back();
    rows.push_back(cells);
  }
  return rows;
}

TEST(CsvExport, CorrectedCsvHasOneRowPerSampleWithExactValuesAndImpactFlags) {
  const testing::ScratchDir dir("csv");
  const core::Block block = testing::PaperLikeBlock();
  testing::PlanarRockingSpec spec;
  const auto motion = testing::SimulatePlanarRocking(block, spec);
  const Recording rec = testing::MeasurePlanar(motion, spec.rate_hz, testing::RealisticImu()).recording;
  const MetricsSummary m = ComputeTrialMetrics(rec, block, {});
  WriteCorrectedCsv(dir / "c.csv", dir / "c_impacts.csv", rec, m);
  const auto rows = ReadCsv(dir / "c.csv");
  ASSERT_EQ(rows.size(), rec.size() + 1);
  EXPECT_EQ(rows[0].front(), "time_s");
  EXPECT_EQ(rows[0].back(), "anchor_x");
  std::size_t flagged = 0;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    ASSERT_EQ(rows[i].size(), 12u);
    flagged += rows[i][10] == "1" ? 1 : 0;
  }
  EXPECT_EQ(flagged, m.correction.impacts_y.size());
  // Shortest round-trip formatting: the text reads back to the same double.
  const std::size_t k = 300;
  EXPECT_EQ(std::stod(rows[k + 1][8]), m.correction.euler_corrected_zyx[k][1]);
  EXPECT_EQ(std::stod(rows[k + 1][2]), rec.w_B[k].y());
  const auto impacts = ReadCsv(dir / "c_impacts.csv");
  EXPECT_EQ(impacts.size(), 1 + m.correction.impacts_y.size() + m.correction.anchors_x.size());
  EXPECT_EQ(impacts[1][0], "phi_y");
  EXPECT_EQ(std::stod(impacts[1][1]), m.correction.impacts_y[0].t_s);
}

TEST(CsvExport, SummaryCsvLeavesMissingValuesEmptyAndQuotesText) {
  const testing::ScratchDir dir("csv");
  CampaignSummary s;
  TrialRow t;
  t.trial_id = "T1", t.block_id = "B1", t.position = "A", t.status = MetricsStatus::kTooFewPeaks;
  t.message = "only 2 peaks, need 3";
  t.opmf = 0.05;
  s.trials = {t};
  s.groups = GroupTrials(s.trials);
  WriteSummaryCsv(dir / "g.csv", dir / "t.csv", s);
  std::ifstream in(dir / "t.csv");
  std::string header, row;
  std::getline(in, header);
  std::getline(in, row);
  EXPECT_EQ(row, "T1,B1,A,0,0,0,too_few_peaks,0.05,,,0,0,\"only 2 peaks, need 3\",identity,0,,,");
  const auto groups = ReadCsv(dir / "g.csv");
  ASSERT_EQ(groups.size(), 2u);
  EXPECT_EQ(groups[1][7], "0.05");  // opmf_mean
  EXPECT_EQ(groups[1][8], "");      // opmf_std of one value
}

}  // namespace
}  // namespace rockfit::io
