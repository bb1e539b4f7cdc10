// Values of the JSON documents every command writes (--json) and Python returns as dictionaries.
#pragma once

#include <optional>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

namespace rockfit::app {

nlohmann::json ToJson(const Eigen::Vector3d& v);
// null for a missing value (JSON has no NaN or infinity): an empty optional, or a value that is not finite.
nlohmann::json OrNull(const std::optional<double>& value);
nlohmann::json OrNull(double value);
// Prints one JSON object on stdout (pretty, 2 spaces).
void PrintJson(const nlohmann::json& object);

}  // namespace rockfit::app
