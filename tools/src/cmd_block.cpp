// `rockfit block`: the block model of docs/design.md §2 — mass, inertia and base vertices.
#include <iostream>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "command_registry.hpp"

namespace rockfit::tools {
namespace {

struct BlockCommand {
  BlockArgs block;
  bool json = false;
};

int RunBlock(const BlockCommand& cmd) {
  const core::Block block = MakeBlock(cmd.block);
  const Eigen::Matrix3d& theta = block.inertia_C_B();
  if (cmd.json) {
    nlohmann::json out;
    out["b1"] = block.b1();
    out["b2"] = block.b2();
    out["h"] = block.h();
    out["mass"] = block.mass();
    out["density"] = block.density();
    out["inertia_com_B"] = {theta(0, 0), theta(1, 1), theta(2, 2)};
    for (int k = 1; k <= 4; ++k) out["vertices_B"]["V" + std::to_string(k)] = ToJson(block.p_BV_B(k));
    PrintJson(out);
    return kExitOk;
  }
  std::cout << fmt::format("block 2b1 × 2b2 × 2h = {:.4f} × {:.4f} × {:.4f} m\n", 2 * block.b1(), 2 * block.b2(),
                           2 * block.h())
            << fmt::format("mass      {:.6g} kg   (density {:.6g} kg/m³)\n", block.mass(), block.density())
            << fmt::format("Θ (COM)   diag({:.6g}, {:.6g}, {:.6g}) kg·m²\n", theta(0, 0), theta(1, 1), theta(2, 2));
  for (int k = 1; k <= 4; ++k) {
    const Eigen::Vector3d p = block.p_BV_B(k);
    std::cout << fmt::format("V{}        ({:+.4f}, {:+.4f}, {:+.4f}) m\n", k, p.x(), p.y(), p.z());
  }
  return kExitOk;
}

const CommandRegistration kRegistration([](CLI::App& root) {
  auto cmd = std::make_shared<BlockCommand>();
  CLI::App* app = root.add_subcommand("block", "Show the block model: mass, inertia about the COM, base vertices");
  AddBlockOptions(*app, cmd->block);
  app->add_flag("--json", cmd->json, "Print one JSON object");
  app->callback([cmd] { SetExitCode(RunBlock(*cmd)); });
});

}  // namespace
}  // namespace rockfit::tools
