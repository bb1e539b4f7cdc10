// `rockfit impact edge|facet`: evaluate one impact map of the paper (Sect. 4.4–4.7, docs/design.md §3) for a given
// block, contact, pre-impact angular velocity and impact parameters.
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <fmt/format.h>

#include "cli_common.hpp"
#include "command_registry.hpp"
#include "rockfit/app/impact_evaluation.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/core/impact_maps.hpp"

namespace rockfit::tools {
namespace {

constexpr const char* kExitCodesHelp =
    "Exit codes: 0 status ok; 1 bad arguments; 3 the map has no single answer (status singular, infeasible or\n"
    "ambiguous) — the result, with the status and every candidate, is still printed.";

struct EdgeCommand {
  BlockArgs block;
  int pivot = 0;
  int landing = 0;
  double tilt_rad = 0.0;
  std::string omega_minus;
  double lambda = 1.0;
  double tau = 0.0;
  bool json = false;
};

struct FacetCommand {
  BlockArgs block;
  std::string pivot_edge = "1,2";
  std::string omega_minus;
  double lambda_lat = 0.0;
  double lambda_lon = 1.0;
  std::optional<double> tau;
  bool json = false;
};

std::string FormatVector(const Eigen::Vector3d& v) { return fmt::format("({:+.9f}, {:+.9f}, {:+.9f})", v.x(), v.y(), v.z()); }

std::string YesNo(bool value) { return value ? "yes" : "no"; }

void PrintOutcomeTable(const core::ImpactOutcome& out, const char* bounds_name, const char* omega_plus_frame) {
  const bool ok = out.status == core::ImpactStatus::kOk;
  std::cout << fmt::format("status          {}\n", core::ToString(out.status));
  std::cout << fmt::format("contact before  {}\n", out.contact_before.ToString());
  if (ok) {
    std::cout << fmt::format("contact after   {}\n", ContactAfterJson(out).get<std::string>())
              << fmt::format("ω⁻ {:<12} {} rad/s\n", omega_plus_frame, FormatVector(out.w_minus_W))
              << fmt::format("ω⁺ {:<12} {} rad/s\n", omega_plus_frame, FormatVector(out.w_plus_W));
    if (std::string(omega_plus_frame) == "(W)") {
      std::cout << fmt::format("ω⁺ {:<12} {} rad/s\n", "(B)", FormatVector(out.w_plus_B));
    }
    std::cout << fmt::format("τ               {:+.6e} N·m·s\n", out.tau)
              << fmt::format("energy          before {:.9g} J, after {:.9g} J, ΔE {:+.6e} J\n", out.energy_before_J,
                             out.energy_after_J, out.delta_energy_J)
              << fmt::format("ΔE ≤ 0 (26)     {}\n", YesNo(out.energy_nonincreasing));
  } else {
    std::cout << fmt::format("ω⁻ {:<12} {} rad/s\n", omega_plus_frame, FormatVector(out.w_minus_W))
              << fmt::format("energy          before {:.9g} J\n", out.energy_before_J);
  }
  std::cout << fmt::format("within {:<8} {}\n", bounds_name, YesNo(out.within_geometric_bounds));
}

// Exit code and a hint on stderr for a map without a single answer.
int FinishWithStatus(const core::ImpactOutcome& out, const std::string& hint) {
  if (out.status == core::ImpactStatus::kOk) return kExitOk;
  std::cerr << "rockfit: the impact map returned status '" << core::ToString(out.status) << "'. " << hint << std::endl;
  return kExitNumerical;
}

void PrintWarnings(const std::vector<std::string>& warnings) {
  for (const auto& w : warnings) std::cerr << "rockfit: warning: " << w << std::endl;
}

// ------------------------------------------------------------------------------------------ edge

int RunEdge(const EdgeCommand& cmd) {
  const core::Block block = MakeBlock(cmd.block);
  EdgeImpactArgs args;
  args.pivot = cmd.pivot;
  args.landing = cmd.landing;
  args.tilt_rad = cmd.tilt_rad;
  args.w_minus_W = ParseVector3(cmd.omega_minus, "--omega-minus");
  args.lambda = cmd.lambda;
  args.tau = cmd.tau;
  const ImpactEvaluation result = EvaluateEdgeImpact(block, args, kProgramImpactNames);
  const core::ImpactOutcome& out = result.outcome;
  const std::vector<double>& singular = result.singular_lambdas;
  const std::vector<std::string>& warnings = result.warnings;

  if (cmd.json) {
    PrintJson(EdgeImpactJson(args, result));
  } else {
    std::cout << fmt::format("edge impact     rocking about V{}, edge V{}V{} lands, tilt {} rad\n", cmd.pivot, cmd.pivot,
                             cmd.landing, cmd.tilt_rad)
              << fmt::format("parameters      λ = {}, τ = {} N·m·s\n", cmd.lambda, cmd.tau);
    PrintOutcomeTable(out, "(25)", "(W)");
    std::string roots;
    for (double r : singular) roots += fmt::format("{}{:.9g}", roots.empty() ? "" : ", ", r);
    std::cout << fmt::format("singular at λ   {}\n", roots.empty() ? "none" : roots);
  }
  PrintWarnings(warnings);
  return FinishWithStatus(out, "(18) is singular at this λ: choose a λ away from the listed singular values.");
}

// ----------------------------------------------------------------------------------------- facet

int RunFacet(const FacetCommand& cmd) {
  const core::Block block = MakeBlock(cmd.block);
  const int b = ParsePivotEdge(cmd.pivot_edge);
  FacetImpactArgs args;
  args.b = b;
  args.w_minus_B = ParseVector3(cmd.omega_minus, "--omega-minus");
  args.lambda_lat = cmd.lambda_lat;
  args.lambda_lon = cmd.lambda_lon;
  args.tau = cmd.tau;
  const ImpactEvaluation result = EvaluateFacetImpact(block, args, kProgramImpactNames);
  const core::ImpactOutcome& out = result.outcome;
  const std::vector<std::string>& warnings = result.warnings;
  const core::FacetTauRule tau_rule = cmd.tau ? core::FacetTauRule::kFixed : core::FacetTauRule::kNoSpin;

  if (cmd.json) {
    PrintJson(FacetImpactJson(args, result));
  } else {
    std::cout << fmt::format("facet impact    pivot edge V{}V{} (b = {}), block flat (W = B)\n",
                             core::Block::WrapVertex(b - 1), b, b)
              << fmt::format("parameters      λ_lat = {}, λ_lon = {}, τ rule {}{}\n", cmd.lambda_lat, cmd.lambda_lon,
                             core::ToString(tau_rule),
                             cmd.tau ? fmt::format(" (τ = {} N·m·s)", *cmd.tau) : std::string(" (24)"));
    PrintOutcomeTable(out, "(27)", "(W = B)");
    std::cout << "candidates      vertex  status     (22)  (23)  feasible  ω⁺ [rad/s]                                 τ [N·m·s]\n";
    for (const core::FacetCandidate& c : out.candidates) {
      if (c.status != core::ImpactStatus::kOk) {
        std::cout << fmt::format("                {:<7} {:<10} -     -     no\n", c.contact.ToString(), core::ToString(c.status));
        continue;
      }
      std::cout << fmt::format("                {:<7} {:<10} {:<5} {:<5} {:<9} {} {:+.6e}\n", c.contact.ToString(),
                               core::ToString(c.status), YesNo(c.impulse_lifts), YesNo(c.no_penetration),
                               YesNo(c.feasible), FormatVector(c.w_plus), c.tau);
    }
  }
  PrintWarnings(warnings);
  std::string hint;
  if (out.status == core::ImpactStatus::kSingular) {
    hint = "(18) is singular for these parameters: move λ_lat/λ_lon away from this point.";
  } else if (tau_rule == core::FacetTauRule::kFixed) {
    hint = "With a fixed --tau the facet map need not have exactly one feasible vertex (paper Fig. 11): see the "
           "candidates, or drop --tau to use the no-spin rule (24).";
  } else {
    hint = "No post-impact vertex satisfies (22)–(23): check that --omega-minus brings the base down onto the ground "
           "(see the candidates).";
  }
  return FinishWithStatus(out, hint);
}

// -------------------------------------------------------------------------------------- register

const CommandRegistration kRegistration([](CLI::App& root) {
  CLI::App* impact = root.add_subcommand("impact", "Evaluate one impact map of Várkonyi, Kocsis & Ther (2021): edge or facet");
  impact->require_subcommand(1);

  auto edge = std::make_shared<EdgeCommand>();
  CLI::App* e = impact->add_subcommand(
      "edge",
      "Edge impact (19)–(20): the block rocks about base vertex V_b (--pivot) until the base edge V_bV_a (--landing) "
      "hits the ground. ω⁻ and ω⁺ are in the world frame W (z up) at the impact attitude: the block rotated "
      "about that edge by --tilt, the rest of the base above the ground.");
  AddBlockOptions(*e, edge->block);
  e->add_option("--pivot", edge->pivot, "Pre-impact contact vertex V_b: 1, 2, 3 or 4")->required()->group("Impact");
  e->add_option("--landing", edge->landing, "Post-impact contact vertex V_a: a neighbour of V_b")->required()->group("Impact");
  e->add_option("--tilt", edge->tilt_rad, "Angle of the base above the ground about the edge V_bV_a [rad], in [0, π/2]")
      ->capture_default_str()->group("Impact");
  e->add_option("--omega-minus", edge->omega_minus, "Pre-impact angular velocity X,Y,Z in W [rad/s]")->required()->group("Impact");
  e->add_option("--lambda", edge->lambda, "λ of (19): the resultant at (r_a+r_b)/2 + λ(r_a−r_b)/2; (25) is −1 ≤ λ ≤ 1")
      ->capture_default_str()->group("Impact");
  e->add_option("--tau", edge->tau, "Vertical angular impulse τ [N·m·s]")->capture_default_str()->group("Impact");
  e->add_flag("--json", edge->json,
              "Print one JSON object: kind, status, contact_before, contact_after, omega_minus, omega_plus (W), "
              "omega_plus_body (B), tau, energy_before, energy_after, delta_energy (26), within_bounds (25), "
              "energy_nonincreasing, singular_lambdas, pivot, landing, tilt, lambda, units, warnings");
  e->footer(kExitCodesHelp);
  e->callback([edge] { SetExitCode(RunEdge(*edge)); });

  auto facet = std::make_shared<FacetCommand>();
  CLI::App* f = impact->add_subcommand(
      "facet",
      "Facet impact (18)+(21): the flat block, rocking about the base edge V_{b−1}V_b, lands on its base. Every base "
      "vertex is a candidate post-impact contact, tested against (22)–(23). Default: τ from the no-spin rule (24) "
      "(the unified map of Sect. 4.7); --tau fixes τ instead. W = B (the block is flat).");
  AddBlockOptions(*f, facet->block);
  f->add_option("--pivot-edge", facet->pivot_edge,
                "Pre-impact pivot edge I,J of neighbouring vertices; taken in cyclic order as V_{b−1}V_b, so 1,2 and 2,1 "
                "both mean V1V2 with b = 2")
      ->capture_default_str()->group("Impact");
  f->add_option("--omega-minus", facet->omega_minus,
                "Pre-impact angular velocity X,Y,Z [rad/s]; falling about V1V2 is (0,+ω,0)")
      ->required()->group("Impact");
  f->add_option("--lambda-lat", facet->lambda_lat, "λ_lat of (21); (27) is −1 ≤ λ_lat ≤ 1")->capture_default_str()->group("Impact");
  f->add_option("--lambda-lon", facet->lambda_lon, "λ_lon of (21); (27) is −1 ≤ λ_lon ≤ 1")->capture_default_str()->group("Impact");
  f->add_option("--tau", facet->tau, "Fixed vertical angular impulse τ [N·m·s] instead of the no-spin rule (24)")->group("Impact");
  f->add_flag("--json", facet->json,
              "Print one JSON object: kind, status, contact_before, contact_after, omega_minus, omega_plus, "
              "omega_plus_body, tau, tau_rule, energy_before, energy_after, delta_energy (26), within_bounds (27), "
              "energy_nonincreasing, candidates (contact, status, feasible, impulse_lifts_22, no_penetration_23, "
              "omega_plus, tau), pivot_edge, b, lambda_lat, lambda_lon, units, warnings");
  f->footer(kExitCodesHelp);
  f->callback([facet] { SetExitCode(RunFacet(*facet)); });
});

}  // namespace
}  // namespace rockfit::tools
