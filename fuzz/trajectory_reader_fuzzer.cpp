// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer harness: any bytes as a tool's trajectory CSV. The reader may only answer with
// roifem::Error (an InputError naming the file and line), or a path whose samples it checked:
// times increasing from (0, 0, 0, 0), finite, two or more; anything else is a bug.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "common/errors.hpp"
#include "scenario/trajectory_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const roifem::model::ToolPath path =
        roifem::scenario::parse_trajectory(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.csv");
    const auto& t = (*path.trajectory)[0].samples->t;
    if (t.size() < 2 || t.front() != 0) std::abort();
    for (std::size_t i = 1; i < t.size(); ++i)
      if (!(t[i] > t[i - 1]) || !std::isfinite(t[i])) std::abort();
    for (double s : {0.0, t.back() / 3, t.back(), 2 * t.back()})
      if (!path.at(s).allFinite() || !path.velocity(s).allFinite()) std::abort();
  } catch (const roifem::Error&) {
  }
  return 0;
}
