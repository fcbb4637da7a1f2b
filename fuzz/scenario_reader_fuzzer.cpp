// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer harness: any bytes as a scenario file. The reader may only answer with roifem::Error
// (an InputError naming file, line and key); anything else (a crash, a sanitizer report, another
// exception type) is a bug.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "common/errors.hpp"
#include "scenario/scenario.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    (void)roifem::scenario::parse_scenario(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.toml",
                                           "/nonexistent");
  } catch (const roifem::Error&) {
  }
  return 0;
}
