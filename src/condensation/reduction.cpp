// SPDX-License-Identifier: GPL-3.0-or-later
#include "condensation/reduction.hpp"

#include <array>
#include <cstdio>

#include "common/did_you_mean.hpp"
#include "common/errors.hpp"
#include "condensation/pod_basis.hpp"
#include "condensation/static_basis.hpp"

namespace roifem::condensation {

namespace {

constexpr std::array<ReductionInfo, 4> table{{
    {.key = "static",
     .description = "the paper's static condensation: K~ = K_dd - K_ds K_ss^-1 K_sd; the static part answers without inertia"},
    {.key = "guyan",
     .carries_mass = true,
     .description = "the static part's mass carried into the ROI through the static modes, M~ = T^T M T"},
    {.key = "craig-bampton",
     .counted = true,
     .takes_cutoff = true,
     .carries_mass = true,
     .make_basis = fixed_interface_modes,
     .description = "K fixed-interface modes of (K_ss, M_ss) as extra generalized coordinates"},
    {.key = "pod",
     .counted = true,
     .carries_mass = true,
     .make_basis = pod_modes,
     .learns_from_loads = true,
     .description = "K fixed-interface vectors learnt from the full model's step responses (mass-weighted POD)"},
}};

/// K from "PREFIX-K" with K a positive integer, or 0.
Index positive_count_after(const std::string& label, std::string_view key) {
  const std::string prefix = std::string(key) + "-";
  if (label.rfind(prefix, 0) != 0 || label.size() == prefix.size() ||
      label.find_first_not_of("0123456789", prefix.size()) != std::string::npos)
    return 0;
  return std::stol(label.substr(prefix.size()));
}

}  // namespace

std::span<const ReductionInfo> reduction_table() { return table; }

const ReductionInfo& reduction_named(std::string_view key) {
  for (const auto& info : table)
    if (info.key == key) return info;
  throw Error("internal: no reduction is named '" + std::string(key) + "'");
}

std::string reduction_key_list() {
  std::string list;
  for (const auto& info : table) list += (list.empty() ? "" : ", ") + std::string(info.key);
  return list;
}

std::string reduction_label_forms() {
  std::string forms;
  for (const auto& info : table) forms += (forms.empty() ? "" : ", ") + std::string(info.key) + (info.counted ? "-K" : "");
  return forms;
}

std::string quoted_keys(bool ReductionInfo::*flag) {
  std::string first, others;
  for (const auto& info : table) {
    if (!(info.*flag)) continue;
    const std::string quoted = "\"" + std::string(info.key) + "\"";
    if (first.empty())
      first = quoted;
    else
      others += (others.empty() ? "" : ", ") + quoted;
  }
  return others.empty() ? first : first + " (or " + others + ")";
}

std::string Reduction::label() const {
  std::string key(info().key);
  if (!info().counted) return key;
  if (modes > 0 || !info().takes_cutoff) return key + "-" + std::to_string(modes);
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "-below-%grad/s", cutoff_rad_s);
  return key + buffer;
}

Reduction parse_reduction(const std::string& label) {
  std::vector<std::string> keys;
  for (const auto& info : table) {
    keys.push_back(std::string(info.key) + (info.counted ? "-K" : ""));
    if (!info.counted && label == info.key) return {.kind = &info};
    if (info.counted) {
      if (const Index count = positive_count_after(label, info.key); count > 0) return {.kind = &info, .modes = count};
    }
  }
  // Compared as a form: "craig-bampten-10" as "craig-bampten-K".
  const std::size_t digits = label.find_last_not_of("0123456789") + 1;
  const std::string form = digits < label.size() ? label.substr(0, digits) + "K" : label;
  throw InputError("unknown reduction '" + label + "'" + did_you_mean(form, keys) + ": use " + reduction_label_forms() +
                   " (K modes or POD vectors, K >= 1)");
}

}  // namespace roifem::condensation
