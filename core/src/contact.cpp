#include "rockfit/core/contact.hpp"

#include "rockfit/core/errors.hpp"

namespace rockfit::core {

Contact Contact::Edge(int i, int j) {
  if (!Block::AreNeighbours(i, j)) {
    throw InvalidArgument("a base edge needs two neighbouring vertices (V1V2, V2V3, V3V4 or V4V1), got V" +
                          std::to_string(Block::WrapVertex(i)) + " and V" + std::to_string(Block::WrapVertex(j)));
  }
  const int wi = Block::WrapVertex(i);
  const int wj = Block::WrapVertex(j);
  // Cyclic order: the second vertex follows the first (V4V1 wraps around).
  return Block::WrapVertex(wi + 1) == wj ? Contact{wi, wj} : Contact{wj, wi};
}

std::string Contact::ToString() const {
  if (first == 0) return "none";
  std::string text = "V" + std::to_string(first);
  if (second != 0) text += "V" + std::to_string(second);
  return text;
}

}  // namespace rockfit::core
