// Fuzz target body: a ground-motion record as `rockfit respond --record FILE` reads it. The first byte picks
// the reader: even → PEER AT2 (io::ParsePeerAt2 on the rest, in memory), odd → ground-motion CSV
// (io::ReadGroundMotionCsv on the rest written to a file, in g, with a time step for files without a time
// column). A record that is returned must keep the readers' promises: NPTS values, a finite positive step,
// finite accelerations, components of one length.
#pragma once
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "fuzz_input.hpp"
#include "rockfit/io/ground_motion_csv.hpp"
#include "rockfit/io/peer_at2.hpp"

namespace rockfit::fuzz {

namespace ground_motion_detail {

[[noreturn]] inline void Violated(const char* what) {
  std::fprintf(stderr, "rockfit fuzz: ground-motion record invariant violated: %s\n", what);
  std::abort();
}

inline void CheckStep(double dt_s) {
  if (!(std::isfinite(dt_s) && dt_s > 0.0)) Violated("time step not finite and positive");
}

inline void CheckValues(const std::vector<double>& values) {
  for (double v : values) {
    if (!std::isfinite(v)) Violated("non-finite acceleration");
  }
}

}  // namespace ground_motion_detail

inline void GroundMotion(std::string_view input) {
  namespace d = ground_motion_detail;
  if (input.empty()) return;
  const bool csv = (static_cast<unsigned char>(input.front()) & 1u) != 0;
  const std::string_view body = input.substr(1);
  if (!csv) {
    ExpectDocumentedOutcome([&] {
      const io::PeerRecord record = io::ParsePeerAt2(std::string(body), "fuzz.AT2");
      if (record.accel_g.size() != record.npts) d::Violated("value count differs from NPTS");
      d::CheckStep(record.dt_s);
      d::CheckValues(record.accel_g);
    });
    return;
  }
  static const ScratchDir dir;
  dir.Clear();
  const auto file = dir.Write("record.csv", body);
  ExpectDocumentedOutcome([&] {
    io::CsvGroundMotionOptions options;
    options.dt_s = 0.01;
    const io::GroundMotionComponents record = io::ReadGroundMotionCsv(file, options);
    d::CheckStep(record.dt_s);
    if (record.accel_m_s2.empty() || record.accel_m_s2.size() > 3) d::Violated("not one to three components");
    if (record.roles.size() != record.accel_m_s2.size()) d::Violated("roles and components differ in number");
    for (const auto& component : record.accel_m_s2) {
      if (component.size() != record.accel_m_s2.front().size()) d::Violated("components differ in length");
      d::CheckValues(component);
    }
  });
}

}  // namespace rockfit::fuzz
