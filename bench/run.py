"""`make bench`: figures printed as ratios against a reference measured in the same run.

- profiles: jerk-limited planning time next to Ruckig's (same random requests), and the
  duration ratio (time-optimality: must print 1.000000);
- cycle: cost of one cycle of one axis in a move (median, microseconds), and simulated
  seconds per wall-clock second for a 4-axis machine at T = 1 ms (reference: real time);
- sync: cost of one cycle of a coupled slave (gear, cam of 2500 points, cam of laws), next
  to a slave holding still;
- compax: one machine cycle of the COMPAX cam slave on a 2500-point curve, with and without
  label correction (reference: real time);
- fs701: the flying shear line of examples/flying_shear.toml after commissioning, simulated
  seconds per wall-clock second and cost of one cycle, scope on and off (reference: real time);
  and the cut accuracy of the three FS701 examples (issue 4's quality bars: deterministic
  figures in carriage increments, no timing);
- examples: every machine in examples/ running its job: us per cycle, real-time factor and
  deterministic bytecodes per cycle (issue 18's table; bar >= 100x);
- serve: cycle lateness of `axisline serve` at 1 ms, idle and with 50 clients on each endpoint,
  beside a bare Python loop sleeping to the same deadlines in the same run;
- sweep: a 40-case FS701 sweep in this process and on a Dask LocalCluster of 1 and 2 workers
  (cases/s), the checks before the run, the cluster start and the scheduling overhead per case;
- cia402: one CANopen axis (CiA 402, CSP) per cycle on the virtual bus with a simulated drive, the
  axes that fit a 1 ms cycle, and the wire time per axis at 1 Mbit/s;
- clm: every CLM example (examples/*_clm.toml: programs, Logic Task, axis functions, plant) at
  its 2 ms NC cycle, simulated seconds per wall-clock second (reference: real time).

Timings are printed, never asserted: they belong here, not in the unit tests.
"""

from __future__ import annotations

import random
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from bench_clm import bench_clm  # noqa: E402
from bench_cycle import bench_cycle  # noqa: E402
from bench_examples import bench_examples  # noqa: E402
from bench_compax import bench_compax  # noqa: E402
from bench_fs701 import bench_fs701, cut_accuracy  # noqa: E402
from bench_profiles import bench_profiles  # noqa: E402
from bench_serve import bench_serve  # noqa: E402
from bench_sync import bench_sync  # noqa: E402

from axisline.drives.bench import bench_cia402  # noqa: E402
from axisline.sweep.bench import bench_sweep  # noqa: E402


def main() -> None:
    random.seed(7)
    print("axisline benchmarks (figures, not pass/fail)\n")
    bench_profiles()
    print()
    bench_cycle()
    print()
    bench_sync()
    print()
    bench_fs701()
    print()
    cut_accuracy()
    print()
    bench_compax()
    print()
    bench_clm()
    print()
    bench_examples()
    print()
    bench_serve()
    print()
    bench_sweep()
    print()
    bench_cia402()


if __name__ == "__main__":
    main()
