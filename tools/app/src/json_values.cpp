#include "rockfit/app/json_values.hpp"

#include <cmath>
#include <iostream>

namespace rockfit::app {

nlohmann::json ToJson(const Eigen::Vector3d& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); }

nlohmann::json OrNull(const std::optional<double>& value) { return value ? OrNull(*value) : nlohmann::json(); }
nlohmann::json OrNull(double value) { return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(); }

void PrintJson(const nlohmann::json& object) { std::cout << object.dump(2) << std::endl; }

}  // namespace rockfit::app
