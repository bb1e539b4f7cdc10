// The `rockfit plot` command group. Every kind of figure (cmd_plot.cpp: euler, summary; later fit, parameters,
// regions) adds itself as a subcommand of PlotApp(root) from its own CommandRegistration, in any order.
#pragma once

#include <filesystem>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

namespace rockfit::tools {

// The "plot" subcommand of `root`, created on first use.
CLI::App& PlotApp(CLI::App& root);

// -o/--output (required, .png or .svg), --width, --height, --json.
struct PictureArgs {
  std::string output;
  int width_px = 1200;
  int height_px = 900;
  bool json = false;
};
void AddPictureOptions(CLI::App& app, PictureArgs& args, int default_width_px, int default_height_px);

// The keys every `rockfit plot KIND --json` prints: kind, output, format ("png" or "svg"), width_px, height_px.
// Each kind adds its own.
nlohmann::json PictureJson(const std::string& kind, const PictureArgs& args);
// What every plot prints when its picture is written: with --json the PictureJson object updated with
// `details`, else "written FILE". Returns kExitOk.
int ReportPicture(const std::string& kind, const PictureArgs& args, const nlohmann::json& details);

}  // namespace rockfit::tools
