// The PEER "AT2" accelerogram text format (PEER strong-motion database and the records its users pass on):
// free text lines, a line with the number of points and the time step, then the accelerations in units of g,
// several to a line. Variants read (io/README.md, "Ground-motion records"):
//  * `NPTS=  4000, DT= .01000 SEC` (PEER), `NPTS=  12000, dt=  .00500` (lower case, no unit), and the
//    NGA form `7998   0.0050   NPTS, DT` (numbers first);
//  * the NPTS line anywhere in the first ten lines (free text before it, e.g. three lines of description);
//  * values in E notation without a leading zero (`-.6490293E-04`), or fixed 10-character fields (8F10.5),
//    also when a negative value fills its field and touches the one before;
//  * LF, CRLF and CR CR LF line ends; a short last line.
// The number of values must equal NPTS (a wrong count is a bad file, exit code 2).
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace rockfit::io {

struct PeerRecord {
  std::string source;                    // the file, for messages and provenance
  std::vector<std::string> header_lines;  // the lines before the data, trimmed
  std::size_t npts = 0;
  double dt_s = 0.0;
  std::vector<double> accel_g;  // NPTS values [g]
  // Largest |value| [g].
  double PeakAbs_g() const;
};

// Throws BadInput (file:line:column, what was found and expected, what to do) for a file that is not a
// readable AT2 record.
PeerRecord ReadPeerAt2(const std::filesystem::path& path);
// The same for text in memory; `display_name` stands for the file in messages.
PeerRecord ParsePeerAt2(const std::string& text, const std::string& display_name);

// The record as AT2 text: the header lines (padded to three), `NPTS=  N, DT= .00500 SEC`, then five values a
// line in E notation with 7 significant digits (`   .1181069E-02`), as the PEER database writes them.
std::string FormatPeerAt2(const PeerRecord& record);

}  // namespace rockfit::io
