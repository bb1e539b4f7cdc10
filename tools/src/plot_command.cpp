#include "plot_command.hpp"

#include <iostream>

#include "cli_common.hpp"
#include "rockfit/app/gnuplot.hpp"

namespace rockfit::tools {

CLI::App& PlotApp(CLI::App& root) {
  const auto existing = root.get_subcommands([](CLI::App* app) { return app->get_name() == "plot"; });
  if (!existing.empty()) return *existing.front();
  CLI::App* plot = root.add_subcommand(
      "plot", "Draw a figure with gnuplot as PNG or SVG (by the extension of -o): euler (raw and corrected Euler "
              "angles, the paper's Fig. 5), summary (OPMF and AVRF against b2, Fig. 6), fit (measured and simulated "
              "ω, Fig. 14), parameters (fitted parameters per block and position, Fig. 15), fragility (fragility curves "
              "with their binomial bands)");
  plot->require_subcommand(1);
  return *plot;
}

void AddPictureOptions(CLI::App& app, PictureArgs& args, int default_width_px, int default_height_px) {
  args.width_px = default_width_px;
  args.height_px = default_height_px;
  app.add_option("-o,--output", args.output, "Picture to write: FILE.png (pngcairo) or FILE.svg")->required()->group("Output");
  app.add_option("--width", args.width_px, "Width [px]")->capture_default_str()->group("Output");
  app.add_option("--height", args.height_px, "Height [px]")->capture_default_str()->group("Output");
  app.add_flag("--json", args.json, "Print one JSON object: kind, output, format, width_px, height_px")->group("Output");
}

nlohmann::json PictureJson(const std::string& kind, const PictureArgs& args) {
  return {{"kind", kind},
          {"output", args.output},
          {"format", ImageFormatFor(args.output) == ImageFormat::kPng ? "png" : "svg"},
          {"width_px", args.width_px},
          {"height_px", args.height_px}};
}

int ReportPicture(const std::string& kind, const PictureArgs& args, const nlohmann::json& details) {
  if (args.json) {
    nlohmann::json j = PictureJson(kind, args);
    j.update(details);
    PrintJson(j);
  } else {
    std::cout << "written " << args.output << "\n";
  }
  return kExitOk;
}

}  // namespace rockfit::tools
