// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// One haptic measurement: a generated brain condensed onto an ROI, a tool holding the ROI's
/// wall nodes nearest the surgical target, steered along a hand path at the device's rate. Each
/// tick takes the hand's new position, steps the condensed model (integrators/haptic_trapezoid.hpp)
/// and returns the force; the plain condensed step (load, step, displacement out) is timed beside
/// it, in blocks taking turns so that the machine's drifts fall on both alike.
///
/// Beside each tick's wall time the benchmark reads the thread's page faults and context switches
/// (getrusage, outside the timed interval), so that a late tick can be told apart: preempted by
/// another process (an involuntary context switch), a page fault, or neither (the work itself,
/// caches, the BLAS). A control loop that reads as many bytes as the condensed factor's dense block
/// (what a solve reads twice), with no solver, shows the machine's own jitter at the tick's length.
#include <filesystem>
#include <string>

#include "common/types.hpp"

namespace roifem::bench {

struct HapticOptions {
  long tool_nodes = 20;
  long ticks = 10000;  ///< timed, each of plain steps, haptic ticks and the control
  long warmup = 200;
  double rate_hz = 1000;  ///< the device's rate: dt = 1 / rate and the deadline
  int blas_threads = 0;   ///< 0: leave the BLAS's count
  bool lock_memory = false;
  /// The nonlinear tick beside the linear one: the hybrid ROI (neo-Hookean where no node is in
  /// the static part) by modified Newton with this many iterations per tick (0: not measured),
  /// along the hand's path scaled by hand_scale (the paper's material: a rigid tool of 20 nodes
  /// moved 2 mm inverts elements at its edge).
  int newton_iterations = 2;
  double hand_scale = 1;
};

/// Tick statistics (s) and the late ticks' causes.
struct TickStats {
  double median = 0, p99 = 0, p999 = 0, max = 0;
  long late = 0;             ///< ticks over the deadline
  long late_preempted = 0;   ///< of those, with an involuntary context switch
  long late_page_fault = 0;  ///< with a page fault
  long page_faults = 0;      ///< over all timed ticks
  long preemptions = 0;      ///< involuntary context switches over all timed ticks
  std::string serialize(const std::string& prefix) const;
  static TickStats parse(const std::string& text, const std::string& prefix);
};

struct HapticMeasurement {
  long nodes = 0, roi_nodes = 0, system_dofs = 0, interface_dofs = 0, tool_nodes = 0;
  double setup_s = 0;   ///< condensation and factor
  double attach_s = 0;  ///< W and Z for the tool
  double peak_force_N = 0;
  bool memory_locked = false;
  int blas_threads = 0;
  TickStats plain, haptic, control;
  /// The nonlinear tick (newton_iterations > 0): its times, its iterations, its Newton residual
  /// after them (the largest over the ticks, relative to the internal force) and its force's
  /// largest distance from a fully converged Newton step's (relative to the peak force).
  TickStats nonlinear;
  int newton_iterations = 0;
  double newton_residual = 0, force_error_rel = 0;
  long nonlinear_ticks = 0;  ///< ticks the nonlinear run took (fewer than asked where it stopped)
  std::string serialize() const;
  static HapticMeasurement parse(const std::string& text);
};

HapticMeasurement measure_haptic(const std::filesystem::path& mesh_file, Index roi_nodes, const HapticOptions& options);

}  // namespace roifem::bench
