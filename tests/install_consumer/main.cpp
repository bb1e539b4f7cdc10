#include <iostream>

#include "rockfit/core/block.hpp"

int main() {
  const auto block = rockfit::core::Block::FromDensity(0.05, 0.03, 0.2, 2692.0);
  std::cout << "installed rockfit: block mass " << block.mass() << " kg" << std::endl;
  return block.mass() > 0 ? 0 : 1;
}
