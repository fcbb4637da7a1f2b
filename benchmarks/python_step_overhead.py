#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The Python module's overhead per step: a step called from Python against the same step in a C++ loop.

Run (after building; README.md):
    PYTHONPATH=build/release/python /usr/bin/python3 benchmarks/python_step_overhead.py \
        --machine-bounds build/release/benchmarks/roifem_machine_bounds

For each model (the paper's setups 1 and 2 and the full brain, trapezoidal rule, dt = 0.05 s) it
times, in interleaved rounds of --steps steps on the same Simulation:
    C++ loop     Simulation._steps_in_cpp(n): ScenarioStepper::step() n times in C++
    sim.step()   a Python for-loop calling sim.step() n times
    sim.run(n)   the module's run loop (C++, with a Ctrl-C check after each step)
    step + ROI   sim.step() and reading sim.roi_displacement_mm (a copy) every step
and prints each one's median time per step over the rounds and its ratio to the C++ loop's median
(the ratios are measured side by side in one run, so the machine's state cancels).
"""
import argparse
import pathlib
import statistics
import subprocess
import time

import roifem

SCENARIOS = pathlib.Path(__file__).resolve().parents[1] / "scenarios"


def per_step(fn, steps):
    start = time.perf_counter()
    fn(steps)
    return (time.perf_counter() - start) / steps


def python_loop(sim):
    def run(steps):
        for _ in range(steps):
            sim.step()
    return run


def python_loop_reading(sim):
    def run(steps):
        for _ in range(steps):
            sim.step()
            sim.roi_displacement_mm
    return run


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=31)
    parser.add_argument("--steps", type=int, default=200, help="steps per round and variant")
    parser.add_argument("--energy", action="store_true", help="keep the energy ledger (off: the step alone)")
    parser.add_argument("--machine-bounds", help="the roifem_machine_bounds executable, to print the machine's bounds")
    args = parser.parse_args()
    if args.machine_bounds:
        print(subprocess.run([args.machine_bounds], capture_output=True, text=True, check=True).stdout, end="")

    print(f"Python step overhead: {args.rounds} rounds of {args.steps} steps, median per step"
          f" (energy ledger {'on' if args.energy else 'off'})")
    print(f"{'model':8} {'dofs':>6} {'C++ loop':>10} {'sim.step()':>11} {'ratio':>6} {'sim.run(n)':>11} {'ratio':>6}"
          f" {'step + ROI':>11} {'ratio':>6}")
    for name in ("setup1", "setup2", "full"):
        sim = roifem.Simulation(SCENARIOS / f"paper-{name}.toml", energy=args.energy)
        variants = {"cpp": sim._steps_in_cpp, "step": python_loop(sim), "run": lambda n: sim.run(n),
                    "read": python_loop_reading(sim)}
        for fn in variants.values():  # warm up: caches, the allocator, first-touch
            fn(args.steps)
        times = {key: [] for key in variants}
        for _ in range(args.rounds):
            for key, fn in variants.items():
                times[key].append(per_step(fn, args.steps))
        med = {key: statistics.median(t) for key, t in times.items()}
        cells = "".join(f" {med[key] * 1e6:9.2f}us {med[key] / med['cpp']:6.3f}" for key in ("step", "run", "read"))
        print(f"{name:8} {sim.dofs:6d} {med['cpp'] * 1e6:8.2f}us{cells}")


if __name__ == "__main__":
    main()
