// Self-registration of subcommands. Each cmd_*.cpp defines one static CommandRegistration whose
// setup function adds its subcommand (options, help, callback) to the root CLI11 app.
#pragma once

#include <functional>
#include <vector>

namespace CLI {
class App;
}

namespace rockfit::tools {

using CommandSetup = std::function<void(CLI::App& root)>;

// All registered setups, in registration order.
std::vector<CommandSetup>& CommandSetups();

struct CommandRegistration {
  explicit CommandRegistration(CommandSetup setup) { CommandSetups().push_back(std::move(setup)); }
};

// Subcommand callbacks report their exit code here (0 when never set).
void SetExitCode(int code);
int ExitCode();

}  // namespace rockfit::tools
