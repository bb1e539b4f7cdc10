#include "rockfit/io/manifest.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <toml++/toml.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/io/load_options.hpp"
#include "rockfit/io/column_map.hpp"
#include "rockfit/io/mounting.hpp"
#include "rockfit/io/input_limits.hpp"
#include "recording/toml_key_depth.hpp"
#include "text/input_problem.hpp"
#include "text/text_file.hpp"

namespace rockfit::io {

const std::vector<std::string>& ManifestFormats() {
  static const std::vector<std::string> formats{"auto", "ximu-gui", "ximu3", "generic-csv", "rockfit-hdf5"};
  return formats;
}

core::Block BlockSpec::ToBlock() const {
  return density_kg_m3 ? core::Block::FromDensity(b1_m, b2_m, h_m, *density_kg_m3)
                       : core::Block::FromMass(b1_m, b2_m, h_m, *mass_kg);
}

namespace {

SourcePosition PositionOf(const toml::source_region& region) {
  return {static_cast<std::size_t>(region.begin.line), static_cast<std::size_t>(region.begin.column)};
}

std::size_t EditDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

// Builds messages "manifest.toml:LINE:COLUMN: what; what to do".
class Reporter {
 public:
  explicit Reporter(std::string name) : name_(std::move(name)) {}
  [[noreturn]] void ThrowBadInput(SourcePosition where, const std::string& message) const {
    if (where.line == 0) throw BadInput(fmt::format("{}: {}", name_, message));
    throw BadInput(fmt::format("{}:{}:{}: {}", name_, where.line, where.column, message));
  }
  const std::string& name() const { return name_; }

 private:
  std::string name_;
};

void RequireKnownKeys(const Reporter& report, const toml::table& table, const std::string& what,
                      const std::vector<std::string>& allowed) {
  for (const auto& [key, node] : table) {
    const std::string name(key.str());
    if (std::find(allowed.begin(), allowed.end(), name) != allowed.end()) continue;
    std::string hint;
    for (const auto& candidate : allowed) {
      if (EditDistance(name, candidate) <= 2) {
        hint = fmt::format(" (did you mean '{}'?)", candidate);
        break;
      }
    }
    report.ThrowBadInput(PositionOf(key.source()), fmt::format("unknown key '{}' in {}{}; allowed keys: {}", name, what,
                                                               hint, fmt::join(allowed, ", ")));
  }
}

const toml::node* Find(const toml::table& table, const char* key) { return table.get(key); }

// A NUL byte would cut the string short wherever it is used as a C string (a path, a message).
const std::string& WithoutNul(const Reporter& report, const std::string& value, const char* key,
                              const std::string& what, SourcePosition where) {
  if (value.find('\0') != std::string::npos) {
    report.ThrowBadInput(
        where, fmt::format("'{}' in {} holds a NUL byte (\\u0000): {}; remove it", key, what, QuoteCell(value)));
  }
  return value;
}

std::string ReadRequiredString(const Reporter& report, const toml::table& table, const char* key,
                               const std::string& what, SourcePosition table_where) {
  const toml::node* node = Find(table, key);
  if (!node)
    report.ThrowBadInput(table_where, fmt::format("{} has no '{}' (a string); add {} = \"…\"", what, key, key));
  const auto* value = node->as_string();
  if (!value) {
    report.ThrowBadInput(PositionOf(node->source()), fmt::format("'{}' in {} must be a string in quotes", key, what));
  }
  return WithoutNul(report, value->get(), key, what, PositionOf(node->source()));
}

std::string ReadOptionalString(const Reporter& report, const toml::table& table, const char* key,
                               const std::string& what, std::string fallback = {}) {
  const toml::node* node = Find(table, key);
  if (!node) return fallback;
  const auto* value = node->as_string();
  if (!value) {
    report.ThrowBadInput(PositionOf(node->source()), fmt::format("'{}' in {} must be a string in quotes", key, what));
  }
  return WithoutNul(report, value->get(), key, what, PositionOf(node->source()));
}

std::optional<double> ReadOptionalPositive(const Reporter& report, const toml::table& table, const char* key,
                                           const std::string& what, const char* unit) {
  const toml::node* node = Find(table, key);
  if (!node) return std::nullopt;
  double value = 0.0;
  if (const auto* f = node->as_floating_point()) {
    value = f->get();
  } else if (const auto* i = node->as_integer()) {
    value = static_cast<double>(i->get());
  } else {
    report.ThrowBadInput(PositionOf(node->source()), fmt::format("'{}' in {} must be a number [{}]", key, what, unit));
  }
  if (!std::isfinite(value) || value <= 0.0) {
    report.ThrowBadInput(PositionOf(node->source()),
                         fmt::format("'{}' in {} must be a positive number [{}], got {}", key, what, unit, value));
  }
  return value;
}

double ReadRequiredPositive(const Reporter& report, const toml::table& table, const char* key,
                            const std::string& what, const char* unit, SourcePosition table_where) {
  const auto value = ReadOptionalPositive(report, table, key, what, unit);
  if (!value)
    report.ThrowBadInput(table_where, fmt::format("{} has no '{}' (a positive number [{}])", what, key, unit));
  return *value;
}

void RequireValidId(const Reporter& report, const std::string& id, const std::string& what, SourcePosition where) {
  const bool ok = !id.empty() && id != "." && id != ".." && std::all_of(id.begin(), id.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.';
  });
  if (!ok) {
    report.ThrowBadInput(where,
                         fmt::format("{} id {} may only contain letters, digits, '-', '_' and '.' (it names groups "
                                     "in HDF5 files)",
                                     what, QuoteCell(id)));
  }
}

// The array of tables `key` (may be absent); anything else there, or more than kMaxManifestEntries, is an error.
const toml::array* TableArray(const Reporter& report, const toml::table& root, const char* key) {
  const toml::node* node = root.get(key);
  if (!node) return nullptr;
  const auto* array = node->as_array();
  if (!array || !array->is_array_of_tables()) {
    report.ThrowBadInput(PositionOf(node->source()),
                         fmt::format("'{}' must be an array of tables: write each entry as [[{}]]", key, key));
  }
  if (array->size() > kMaxManifestEntries) {
    report.ThrowBadInput(PositionOf((*array)[kMaxManifestEntries].source()),
                         fmt::format("{} [[{}]] entries, more than the {} a manifest may have (docs/file-formats.md, "
                                     "\"Limits\"); split the campaign into several manifests",
                                     array->size(), key, kMaxManifestEntries));
  }
  return array;
}

// The keys that say how to read recordings, in [[trials]] and (as defaults) in [[blocks]]: format, rate, mounting,
// columns; each checked where it is written. Absent keys leave the outputs empty.
void ReadRecordingKeys(const Reporter& report, const toml::table& table, const std::string& what, std::string* format,
                       std::optional<double>* rate_hz, std::string* mounting, std::string* columns) {
  *format = ReadOptionalString(report, table, "format", what);
  if (!format->empty() && !ParseFormatName(*format)) {
    report.ThrowBadInput(
        PositionOf(table.get("format")->source()),
        fmt::format("{}: unknown format '{}'; use one of {}", what, *format, fmt::join(ManifestFormats(), ", ")));
  }
  *rate_hz = ReadOptionalPositive(report, table, "rate", what, "Hz");
  if (*rate_hz && **rate_hz > kMaxRate_hz) {
    report.ThrowBadInput(
        PositionOf(table.get("rate")->source()),
        fmt::format("{}: rate {} Hz is above {} Hz, faster than any IMU rockfit reads", what, **rate_hz, kMaxRate_hz));
  }
  *mounting = ReadOptionalString(report, table, "mounting", what);
  if (!mounting->empty()) {
    try {
      (void)MountingOption::Parse(*mounting);
    } catch (const InvalidArgument& e) {
      report.ThrowBadInput(PositionOf(table.get("mounting")->source()), fmt::format("{}: {}", what, e.what()));
    }
  }
  *columns = ReadOptionalString(report, table, "columns", what);
  if (!columns->empty()) {
    try {
      (void)ColumnMap::Parse(*columns);
    } catch (const InvalidArgument& e) {
      report.ThrowBadInput(PositionOf(table.get("columns")->source()), fmt::format("{}: {}", what, e.what()));
    }
  }
}

BlockSpec ParseBlock(const Reporter& report, const toml::table& table, std::size_t ordinal) {
  BlockSpec block;
  block.where = PositionOf(table.source());
  const std::string anonymous = fmt::format("[[blocks]] number {}", ordinal);
  RequireKnownKeys(report, table, anonymous,
                   {"id", "b1", "b2", "h", "density", "mass", "notes", "format", "columns", "rate", "mounting"});
  block.id = ReadRequiredString(report, table, "id", anonymous, block.where);
  const std::string what = fmt::format("[[blocks]] '{}'", block.id);
  const toml::node* id_node = table.get("id");
  RequireValidId(report, block.id, "block", PositionOf(id_node->source()));
  block.b1_m = ReadRequiredPositive(report, table, "b1", what, "m", block.where);
  block.b2_m = ReadRequiredPositive(report, table, "b2", what, "m", block.where);
  block.h_m = ReadRequiredPositive(report, table, "h", what, "m", block.where);
  block.density_kg_m3 = ReadOptionalPositive(report, table, "density", what, "kg/m³");
  block.mass_kg = ReadOptionalPositive(report, table, "mass", what, "kg");
  if (block.density_kg_m3.has_value() == block.mass_kg.has_value()) {
    report.ThrowBadInput(block.where, fmt::format("{} needs exactly one of 'density' [kg/m³] or 'mass' [kg]{}", what,
                                                  block.mass_kg ? ", not both" : ""));
  }
  block.notes = ReadOptionalString(report, table, "notes", what);
  ReadRecordingKeys(report, table, what, &block.format, &block.rate_hz, &block.mounting, &block.columns);
  return block;
}

TrialSpec ParseTrial(const Reporter& report, const toml::table& table, std::size_t ordinal,
                     const std::filesystem::path& base_dir) {
  TrialSpec trial;
  trial.where = PositionOf(table.source());
  const std::string anonymous = fmt::format("[[trials]] number {}", ordinal);
  RequireKnownKeys(report, table, anonymous,
                   {"id", "block", "position", "files", "format", "rate", "mounting", "columns", "notes"});
  trial.id = ReadRequiredString(report, table, "id", anonymous, trial.where);
  RequireValidId(report, trial.id, "trial", PositionOf(table.get("id")->source()));
  const std::string what = fmt::format("[[trials]] '{}'", trial.id);
  trial.block_id = ReadRequiredString(report, table, "block", what, trial.where);
  trial.position = ReadRequiredString(report, table, "position", what, trial.where);
  if (trial.position.empty())
    report.ThrowBadInput(PositionOf(table.get("position")->source()), what + ": 'position' is empty");
  trial.files_as_written = ReadRequiredString(report, table, "files", what, trial.where);
  if (trial.files_as_written.empty())
    report.ThrowBadInput(PositionOf(table.get("files")->source()), what + ": 'files' is empty");
  const std::filesystem::path files(trial.files_as_written);
  trial.files = files.is_absolute() ? files : (base_dir / files).lexically_normal();
  std::string format;
  ReadRecordingKeys(report, table, what, &format, &trial.rate_hz, &trial.mounting, &trial.columns);
  trial.format = format.empty() ? "auto" : format;
  trial.notes = ReadOptionalString(report, table, "notes", what);
  return trial;
}

}  // namespace

Manifest ParseManifest(std::string_view text, const std::filesystem::path& path) {
  const Reporter report(path.string());
  if (const DottedKeyDepth deep = FindDeepDottedKey(text, kMaxManifestKeyParts); deep.line > 0) {
    report.ThrowBadInput(
        {deep.line, deep.column},
        fmt::format("a dotted key or table name of more than {} parts; rockfit reads keys of up to {} parts "
                    "(a manifest needs at most two, such as [[blocks]] and id): check that this is a "
                    "manifest, or shorten the key",
                    kMaxManifestKeyParts, kMaxManifestKeyParts));
  }
  toml::table root;
  try {
    root = toml::parse(text, path.string());
  } catch (const toml::parse_error& e) {
    report.ThrowBadInput(PositionOf(e.source()), fmt::format("TOML syntax error: {}", e.description()));
  }
  RequireKnownKeys(report, root, "the manifest (top level)", {"blocks", "trials"});
  Manifest manifest;
  manifest.path = path;
  const std::filesystem::path base_dir = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");

  std::map<std::string, SourcePosition> block_ids;
  if (const toml::array* blocks = TableArray(report, root, "blocks")) {
    std::size_t ordinal = 0;
    for (const toml::node& node : *blocks) {
      BlockSpec block = ParseBlock(report, *node.as_table(), ++ordinal);
      const SourcePosition id_where = PositionOf(node.as_table()->get("id")->source());
      if (const auto it = block_ids.find(block.id); it != block_ids.end()) {
        report.ThrowBadInput(id_where,
                             fmt::format("duplicate block id '{}' (first defined at line {}); block ids must be "
                                         "unique",
                                         block.id, it->second.line));
      }
      try {
        (void)block.ToBlock();
      } catch (const InvalidArgument& e) {
        report.ThrowBadInput(block.where, fmt::format("[[blocks]] '{}': {}", block.id, e.what()));
      }
      block_ids[block.id] = id_where;
      manifest.blocks.push_back(std::move(block));
    }
  }
  std::map<std::string, SourcePosition> trial_ids;
  if (const toml::array* trials = TableArray(report, root, "trials")) {
    std::size_t ordinal = 0;
    for (const toml::node& node : *trials) {
      const toml::table& table = *node.as_table();
      TrialSpec trial = ParseTrial(report, table, ++ordinal, base_dir);
      const SourcePosition id_where = PositionOf(table.get("id")->source());
      if (const auto it = trial_ids.find(trial.id); it != trial_ids.end()) {
        report.ThrowBadInput(id_where,
                             fmt::format("duplicate trial id '{}' (first defined at line {}); trial ids must be "
                                         "unique",
                                         trial.id, it->second.line));
      }
      if (block_ids.count(trial.block_id) == 0) {
        std::vector<std::string> known;
        for (const auto& b : manifest.blocks) known.push_back(b.id);
        report.ThrowBadInput(
            PositionOf(table.get("block")->source()),
            fmt::format("[[trials]] '{}' names block '{}', which no [[blocks]] entry defines; known blocks: {}",
                        trial.id, trial.block_id, known.empty() ? "none" : fmt::format("{}", fmt::join(known, ", "))));
      }
      for (const BlockSpec& block : manifest.blocks) {  // the block's defaults for what the trial leaves out
        if (block.id != trial.block_id) continue;
        if (!Find(table, "format") && !block.format.empty()) trial.format = block.format;
        if (!trial.rate_hz) trial.rate_hz = block.rate_hz;
        if (trial.mounting.empty()) trial.mounting = block.mounting;
        if (trial.columns.empty()) trial.columns = block.columns;
      }
      trial_ids[trial.id] = id_where;
      manifest.trials.push_back(std::move(trial));
    }
  }
  if (manifest.blocks.empty() && manifest.trials.empty()) {
    report.ThrowBadInput({}, "the manifest defines no [[blocks]] and no [[trials]]; see io/README.md for the format");
  }
  return manifest;
}

Manifest ReadManifest(const std::filesystem::path& path) {
  return ParseManifest(ReadRegularFile(path, "a manifest (TOML)", kMaxManifestFileBytes), path);
}

const BlockSpec& Manifest::FindBlock(const std::string& id) const {
  for (const auto& block : blocks) {
    if (block.id == id) return block;
  }
  std::vector<std::string> known;
  for (const auto& block : blocks) known.push_back(block.id);
  throw BadInput(fmt::format("{}: no block {}; known blocks: {}", path.string(), QuoteCell(id),
                             known.empty() ? "none" : fmt::format("{}", fmt::join(known, ", "))));
}

const TrialSpec& Manifest::FindTrial(const std::string& id) const {
  for (const auto& trial : trials) {
    if (trial.id == id) return trial;
  }
  std::vector<std::string> known;
  for (const auto& trial : trials) known.push_back(trial.id);
  throw BadInput(fmt::format("{}: no trial {}; known trials: {}", path.string(), QuoteCell(id),
                             known.empty() ? "none" : fmt::format("{}", fmt::join(known, ", "))));
}

}  // namespace rockfit::io
