// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Runs a piece of work in a forked child process, so that each measured model starts from a
/// clean heap and reports its own memory peak, and a model too large for the machine (killed by
/// the OOM killer, or past its time limit) costs one row of the table instead of the whole run.
#include <functional>
#include <map>
#include <string>

namespace roifem::bench {

struct ChildResult {
  bool ok = false;
  std::string output;  ///< what the work returned (ok), or why it failed
};

/// `work` runs in the child; its return value comes back through a pipe. An exception in the
/// child, a signal, or `timeout_s` passing gives ok = false with the reason.
ChildResult run_in_child(const std::function<std::string()>& work, double timeout_s);

/// What the children here return: "key=value" lines, read back into a map.
std::map<std::string, std::string> parse_key_values(const std::string& text);

}  // namespace roifem::bench
