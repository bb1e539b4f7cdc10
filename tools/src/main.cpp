// rockfit — experimental rocking dynamics from the command line. Subcommands live in cmd_*.cpp.
#include <csignal>
#include <exception>
#include <iostream>
#include <new>
#include <string>

#include <CLI/CLI.hpp>

#include "rockfit/app/activity.hpp"
#include "cli_common.hpp"
#include "command_registry.hpp"
#include "rockfit/app/run_limits.hpp"
#include "rockfit/core/errors.hpp"

namespace rockfit::tools {
namespace {
int g_exit_code = kExitOk;
}  // namespace

std::vector<CommandSetup>& CommandSetups() {
  static std::vector<CommandSetup> setups;
  return setups;
}
void SetExitCode(int code) { g_exit_code = code; }
int ExitCode() { return g_exit_code; }

}  // namespace rockfit::tools

int main(int argc, char** argv) {
  using namespace rockfit::tools;
  // A file-size limit (ulimit -f, RLIMIT_FSIZE) would otherwise kill rockfit with SIGXFSZ in the middle of a
  // write; ignored, the write fails with EFBIG and the writers report it (exit code 4) and remove their
  // temporary file, as for a full disk.
  std::signal(SIGXFSZ, SIG_IGN);
  CLI::App app{"rockfit — IMU recordings, 3D impact maps, simulation and fitting of rocking blocks\n"
               "(Várkonyi, Kocsis & Ther 2021, Nonlinear Dynamics). Run `rockfit SUBCOMMAND --help` for details."};
  app.footer(LimitsHelp());
  app.set_version_flag("--version", std::string("rockfit ") + ROCKFIT_VERSION);
  app.require_subcommand(1);
  for (const auto& setup : CommandSetups()) setup(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    std::cerr << "Run with --help to see the allowed options." << std::endl;
    return kExitUsage;
  } catch (const rockfit::InvalidArgument& e) {
    std::cerr << "rockfit: " << e.what() << "\nRun with --help to see the allowed options." << std::endl;
    return kExitUsage;
  } catch (const rockfit::BadInput& e) {
    std::cerr << "rockfit: " << e.what() << std::endl;
    return kExitBadInput;
  } catch (const rockfit::NumericalFailure& e) {
    std::cerr << "rockfit: " << e.what() << std::endl;
    return kExitNumerical;
  } catch (const rockfit::OutputError& e) {
    std::cerr << "rockfit: " << e.what() << std::endl;
    return kExitCannotWrite;
  } catch (const std::bad_alloc&) {
    const std::string what = Activity::Current();
    std::cerr << "rockfit: out of memory" << (what.empty() ? std::string() : " while " + what)
              << ".\nGive the command less to hold (shorter records, fewer levels or samples; the largest inputs and "
                 "their memory are listed under `rockfit --help` and in docs/file-formats.md, \"Limits\") or run it "
                 "where more memory is available."
              << std::endl;
    return kExitNumerical;
  } catch (const std::exception& e) {
    std::cerr << "rockfit: internal error: " << e.what()
              << "\nPlease report this with the command line that caused it." << std::endl;
    return kExitNumerical;
  }
  return ExitCode();
}
