#include "rockfit/app/gnuplot.hpp"

#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string_view>

#include <fmt/format.h>

#include "rockfit/app/output_kind.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/io/atomic_file.hpp"

namespace rockfit::app {

namespace {

std::atomic<unsigned> g_serial{0};  // names this process's scratch directories

std::string ShellQuote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// Removes the scratch directories "rockfit-plot-<pid>-<n>" of processes that no longer run (a plot killed
// by a signal cannot clean up after itself). Best effort: errors are ignored.
void RemoveOrphanedScratchDirectories(const std::filesystem::path& temp_dir) {
  constexpr std::string_view kPrefix = "rockfit-plot-";
  std::error_code ec;
  for (std::filesystem::directory_iterator it(temp_dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.compare(0, kPrefix.size(), kPrefix) != 0) continue;
    const std::size_t dash = name.find('-', kPrefix.size());
    if (dash == std::string::npos) continue;
    long pid = 0;
    try {
      pid = std::stol(name.substr(kPrefix.size(), dash - kPrefix.size()));
    } catch (const std::exception&) {
      continue;
    }
    if (pid <= 0 || pid == static_cast<long>(::getpid())) continue;
    if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;  // alive, or not ours to judge
    std::error_code remove_ec;
    std::filesystem::remove_all(it->path(), remove_ec);
  }
}

bool IsExecutable(const std::filesystem::path& path) {
  struct stat info {};
  return ::stat(path.c_str(), &info) == 0 && S_ISREG(info.st_mode) && ::access(path.c_str(), X_OK) == 0;
}

const char* kInstallHint =
    "gnuplot is needed for plots and was not found; install it with `sudo apt-get install gnuplot-nox` (Debian/Ubuntu), "
    "or set ROCKFIT_GNUPLOT to its path";

// True when gnuplot finished the picture: a PNG ends with its IEND chunk (length 0, "IEND", CRC), an SVG with
// "</svg>". A full disk or a file-size limit can leave gnuplot's output cut short while gnuplot still exits 0.
bool IsCompleteImage(const std::filesystem::path& path, ImageFormat format) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  const std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (format == ImageFormat::kPng) {
    static const std::string kSignature("\x89PNG\r\n\x1a\n", 8);
    static const std::string kEnd("\0\0\0\0IEND\xae\x42\x60\x82", 12);
    return content.size() >= kSignature.size() + kEnd.size() && content.compare(0, 8, kSignature) == 0 &&
           content.compare(content.size() - kEnd.size(), kEnd.size(), kEnd) == 0;
  }
  const std::size_t end = content.rfind("</svg>");
  return end != std::string::npos && content.find_first_not_of(" \t\r\n", end + 6) == std::string::npos;
}

}  // namespace

ImageFormat ImageFormatFor(const std::filesystem::path& output) {
  const std::string extension = app::LowerCaseExtension(output);
  if (extension == ".png") return ImageFormat::kPng;
  if (extension == ".svg") return ImageFormat::kSvg;
  throw InvalidArgument(fmt::format("-o {}: the picture must end in .png or .svg", output.string()));
}

std::optional<std::filesystem::path> FindGnuplot() {
  if (const char* forced = std::getenv("ROCKFIT_GNUPLOT")) {
    if (IsExecutable(forced)) return std::filesystem::path(forced);
    return std::nullopt;
  }
  const char* path_env = std::getenv("PATH");
  std::stringstream dirs(path_env ? path_env : "/usr/bin:/bin");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (dir.empty()) continue;
    const std::filesystem::path candidate = std::filesystem::path(dir) / "gnuplot";
    if (IsExecutable(candidate)) return candidate;
  }
  return std::nullopt;
}

std::string GnuplotString(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("''") : std::string(1, c);
  return quoted + "'";
}

GnuplotFigure::GnuplotFigure() {
  RemoveOrphanedScratchDirectories(std::filesystem::temp_directory_path());
  directory_ = std::filesystem::temp_directory_path() /
               fmt::format("rockfit-plot-{}-{}", ::getpid(), g_serial++);
  std::error_code ec;
  std::filesystem::remove_all(directory_, ec);
  if (!std::filesystem::create_directories(directory_, ec)) {
    throw OutputError(fmt::format("cannot create the temporary directory {}: {}", directory_.string(), ec.message()));
  }
}

GnuplotFigure::~GnuplotFigure() {
  std::error_code ec;
  std::filesystem::remove_all(directory_, ec);
}

std::string GnuplotFigure::AddData(const std::string& name, const std::vector<std::vector<double>>& columns,
                                   const std::vector<std::size_t>& block_starts) {
  const std::filesystem::path path = directory_ / (name + ".dat");
  std::ofstream out(path);
  const std::size_t rows = columns.empty() ? 0 : columns.front().size();
  for (const auto& column : columns) {
    if (column.size() != rows) throw InvalidArgument("GnuplotFigure::AddData: columns of different lengths");
  }
  for (std::size_t r = 0; r < rows; ++r) {
    if (r > 0 && std::find(block_starts.begin(), block_starts.end(), r) != block_starts.end()) out << "\n";
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const double v = columns[c][r];
      out << (c ? " " : "") << (std::isfinite(v) ? fmt::format("{}", v) : std::string("NaN"));
    }
    out << "\n";
  }
  if (!out) throw OutputError(fmt::format("cannot write {}", path.string()));
  return GnuplotString(path.string());
}

void GnuplotFigure::Render(const std::string& body, const std::filesystem::path& output, int width_px,
                           int height_px) const {
  const ImageFormat format = ImageFormatFor(output);
  const std::optional<std::filesystem::path> gnuplot = FindGnuplot();
  if (!gnuplot) throw OutputError(kInstallHint);
  if (width_px < 100 || height_px < 100 || width_px > 20000 || height_px > 20000) {
    throw InvalidArgument(fmt::format("picture size {}×{} px is outside 100…20000", width_px, height_px));
  }
  const std::filesystem::path dir = output.has_parent_path() ? output.parent_path() : std::filesystem::path(".");
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) {
    throw OutputError(fmt::format("cannot write {}: the directory {} does not exist", output.string(), dir.string()));
  }
  // gnuplot draws into the temporary file of an atomic replacement, which is renamed over `output` only when the
  // picture is complete (and removed otherwise).
  io::AtomicReplacement replacement(output);
  const std::filesystem::path& temporary = replacement.temporary();
  const std::string terminal =
      format == ImageFormat::kPng
          ? fmt::format("set terminal pngcairo size {},{} enhanced font 'Sans,10' linewidth 1.2", width_px, height_px)
          : fmt::format("set terminal svg size {},{} dynamic enhanced font 'Sans,10' linewidth 1.2", width_px, height_px);
  const std::filesystem::path script = directory_ / "figure.gp";
  {
    std::ofstream out(script);
    out << terminal << "\nset output " << GnuplotString(temporary.string()) << "\nset encoding utf8\n"
        << body << "\nunset output\n";
    if (!out) throw OutputError(fmt::format("cannot write {}", script.string()));
  }
  const std::filesystem::path messages = directory_ / "gnuplot.err";
  const std::string command = ShellQuote(gnuplot->string()) + " " + ShellQuote(script.string()) + " </dev/null >" +
                              ShellQuote(messages.string()) + " 2>&1";
  const int status = std::system(command.c_str());
  const bool ok = status != -1 && WIFEXITED(status) && WEXITSTATUS(status) == 0;
  if (!ok || !IsCompleteImage(temporary, format)) {
    std::ifstream in(messages);
    std::stringstream text;
    text << in.rdbuf();
    throw OutputError(fmt::format("gnuplot ({}) could not draw {}: {}", gnuplot->string(), output.string(),
                                  text.str().empty() ? "no message" : text.str()));
  }
  replacement.Commit();
}

}  // namespace rockfit::app
