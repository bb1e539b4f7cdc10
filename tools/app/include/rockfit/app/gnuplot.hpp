// Figures through gnuplot (docs/design.md §10): a figure writes its data files into a private temporary directory,
// generates a script, runs gnuplot on it and moves the picture atomically to the requested path. PNG
// (pngcairo) or SVG by the output's extension. Without gnuplot, Render() fails with an OutputError saying how
// to install it; nothing else in rockfit depends on gnuplot. Reusable by every plot (Euler angles, summary,
// fit, parameters, impact-map regions).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace rockfit::app {

enum class ImageFormat { kPng, kSvg };
// ".png" or ".svg" (any case); InvalidArgument naming the option otherwise.
ImageFormat ImageFormatFor(const std::filesystem::path& output);

// The gnuplot executable: $ROCKFIT_GNUPLOT when set (tests use it to simulate a missing gnuplot), else
// `gnuplot` on $PATH. None when not found or not executable.
std::optional<std::filesystem::path> FindGnuplot();

// A string literal for a gnuplot script: in single quotes, with single quotes doubled.
std::string GnuplotString(const std::string& text);

class GnuplotFigure {
 public:
  GnuplotFigure();
  ~GnuplotFigure();
  GnuplotFigure(const GnuplotFigure&) = delete;
  GnuplotFigure& operator=(const GnuplotFigure&) = delete;

  // Writes columns of equal length as a whitespace-separated data file (NaN for missing values, which gnuplot
  // skips) and returns its name as a gnuplot string literal for `plot`. A blank line separates blocks
  // when `block_starts` lists row indices (gnuplot then breaks lines there).
  std::string AddData(const std::string& name, const std::vector<std::vector<double>>& columns,
                      const std::vector<std::size_t>& block_starts = {});

  // Runs `body` (everything after `set terminal` and `set output`) and moves the picture to `output`.
  // OutputError when gnuplot is missing, fails (its message is included) or produces nothing.
  void Render(const std::string& body, const std::filesystem::path& output, int width_px, int height_px) const;

  const std::filesystem::path& directory() const { return directory_; }

 private:
  std::filesystem::path directory_;
};

}  // namespace rockfit::app
