#include "text/header_matching.hpp"

#include <algorithm>
#include <numeric>

#include "text/number_parsing.hpp"

namespace rockfit::io {

std::string NormalizeHeader(std::string_view header) {
  header = TrimSpaces(header);
  std::string text;
  text.reserve(header.size());
  bool in_space = false;
  for (char c : header) {
    if (c == ' ' || c == '\t') {
      in_space = true;
      continue;
    }
    if (in_space) text += ' ';
    in_space = false;
    text += (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
  }
  return text;
}

bool HeaderEquals(std::string_view header, std::string_view expected) {
  return NormalizeHeader(header) == NormalizeHeader(expected);
}

std::size_t EditDistance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> previous(b.size() + 1);
  std::vector<std::size_t> current(b.size() + 1);
  std::iota(previous.begin(), previous.end(), std::size_t{0});
  for (std::size_t i = 1; i <= a.size(); ++i) {
    current[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t substitute = previous[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      current[j] = std::min({previous[j] + 1, current[j - 1] + 1, substitute});
    }
    std::swap(previous, current);
  }
  return previous[b.size()];
}

std::optional<HeaderSuggestion> ClosestHeader(const std::vector<std::string>& candidates,
                                              const std::vector<std::string>& wanted) {
  std::optional<HeaderSuggestion> best;
  for (std::size_t index = 0; index < candidates.size(); ++index) {
    const std::string candidate = NormalizeHeader(candidates[index]);
    if (candidate.empty()) continue;
    for (const std::string& name : wanted) {
      const std::string target = NormalizeHeader(name);
      const std::size_t distance = EditDistance(candidate, target);
      const std::size_t allowed = std::max<std::size_t>(2, target.size() / 4);  // a misspelling, not another name
      if (distance == 0 || distance > allowed) continue;
      if (!best || distance < best->distance) best = HeaderSuggestion{index, distance};
    }
  }
  return best;
}

HeaderParts SplitHeaderUnit(std::string_view header) {
  header = TrimSpaces(header);
  if (!header.empty() && (header.back() == ')' || header.back() == ']')) {
    const std::size_t open = header.rfind(header.back() == ')' ? '(' : '[');
    if (open != std::string_view::npos) {
      return {std::string(TrimSpaces(header.substr(0, open))),
              std::string(TrimSpaces(header.substr(open + 1, header.size() - open - 2)))};
    }
  }
  return {std::string(header), {}};
}

}  // namespace rockfit::io
