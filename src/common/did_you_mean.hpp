// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// "Did you mean" for a name that is not among the valid ones: the closest by edit distance
/// (Levenshtein), when it is close enough to be a typo (at most a third of the longer name, and 2).
#include <algorithm>
#include <string>
#include <string_view>
#include <vector>

namespace roifem {

inline std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

/// The closest candidate (of equally close ones, one that contains `name`) if it is close enough to be a typo of `name`, else the
/// shortest candidate that contains `name` (a name given without its prefix: "esdirk4" for "arkode-esdirk4"), else empty.
inline std::string closest_name(std::string_view name, const std::vector<std::string>& candidates) {
  if (std::find(candidates.begin(), candidates.end(), name) != candidates.end()) return "";  // valid already
  std::string best;
  std::size_t best_distance = 0;
  auto contains_name = [&](const std::string& c) { return c.find(name) != std::string::npos; };
  for (const auto& c : candidates) {
    const std::size_t d = edit_distance(name, c);
    // A tie goes to a candidate that contains the name ("ramp": "ramp_s" before "name").
    if (best.empty() || d < best_distance || (d == best_distance && contains_name(c) && !contains_name(best))) {
      best = c;
      best_distance = d;
    }
  }
  const std::size_t allowed = std::max<std::size_t>(2, std::max(name.size(), best.size()) / 3);
  if (!best.empty() && best_distance > 0 && best_distance <= allowed) return best;
  std::string containing;
  if (name.size() >= 3)
    for (const auto& c : candidates)
      if (c != name && c.find(name) != std::string::npos && (containing.empty() || c.size() < containing.size())) containing = c;
  return containing;
}

/// " (did you mean 'x'?)", or "" when nothing is close.
inline std::string did_you_mean(std::string_view name, const std::vector<std::string>& candidates) {
  const std::string best = closest_name(name, candidates);
  return best.empty() ? std::string() : " (did you mean '" + best + "'?)";
}

}  // namespace roifem
