// A campaign manifest (TOML, docs/design.md §8): the blocks and the trials recorded with them.
//
//   [[blocks]]
//   id = "B3"            # letters, digits, '-', '_', '.'
//   b1 = 0.05            # half-width along x [m]
//   b2 = 0.03            # half-depth along y [m]
//   h  = 0.20            # COM height above the base = half the block height [m]
//   density = 2692       # [kg/m³] — or mass = … [kg], exactly one of the two
//   format = "csv"       # optional: the default format, columns, rate and mounting of this block's trials
//   columns = "phyphox"  #   (each trial may set its own, which wins)
//
//   [[trials]]
//   id = "B3-A-1"
//   block = "B3"         # id of a block above
//   position = "A"       # the block's position (the paper's A/B: upside down or not)
//   files = "raw/B3-A-1" # a file, a file prefix or a directory, relative to the manifest
//   format = "auto"      # optional: auto, ximu-gui, ximu3, generic-csv (or csv), rockfit-hdf5
//   rate = 256           # optional: sample rate [Hz] when the files do not say
//   mounting = "x,-y,-z" # optional: sensor axes on the block (mounting.hpp), identity by default
//   columns = "time=t@ms;gyro=gx,gy,gz@dps;accel=ax,ay,az@g"  # optional: generic CSV column map or preset
//                        # (column_map.hpp: which columns, their units; "phyphox", "sensor-logger")
//   notes = "…"          # optional
//
// Every mistake is a BadInput naming the manifest, line and column: syntax errors, unknown or misspelt keys
// (with a suggestion), missing keys, wrong types, non-positive sizes, unknown block ids and duplicate ids.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rockfit/core/block.hpp"

namespace rockfit::io {

struct SourcePosition {
  std::size_t line = 0;    // 1-based; 0 when unknown
  std::size_t column = 0;  // 1-based
};

struct BlockSpec {
  std::string id;
  double b1_m = 0.0;
  double b2_m = 0.0;
  double h_m = 0.0;
  std::optional<double> density_kg_m3;
  std::optional<double> mass_kg;
  std::string notes;
  // Defaults for the trials of this block (a trial's own key wins); empty / nullopt: not given.
  std::string format;
  std::string columns;
  std::string mounting;
  std::optional<double> rate_hz;
  SourcePosition where;
  core::Block ToBlock() const;
};

struct TrialSpec {
  std::string id;
  std::string block_id;
  std::string position;
  std::filesystem::path files;      // resolved against the manifest's directory
  std::string files_as_written;
  std::string format = "auto";
  std::optional<double> rate_hz;
  std::string mounting;             // as written; empty: the sensor axes are the block axes
  std::string columns;              // generic CSV column map or preset as written (column_map.hpp); empty: detected
  std::string notes;
  SourcePosition where;
};

struct Manifest {
  std::filesystem::path path;
  std::vector<BlockSpec> blocks;
  std::vector<TrialSpec> trials;
  // Throw BadInput naming the manifest and listing the known ids.
  const BlockSpec& FindBlock(const std::string& id) const;
  const TrialSpec& FindTrial(const std::string& id) const;
};

// The format names listed in messages (load_options.hpp's ParseFormatName also takes "csv").
const std::vector<std::string>& ManifestFormats();

// Reads and checks a manifest file. Throws BadInput (unreadable file, syntax, schema).
Manifest ReadManifest(const std::filesystem::path& path);
// The same from text; `path` names the manifest in messages and anchors the relative `files`.
Manifest ParseManifest(std::string_view text, const std::filesystem::path& path);

}  // namespace rockfit::io
