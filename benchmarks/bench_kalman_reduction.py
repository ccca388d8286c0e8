"""Benchmark of the Kalman estimator's reduced model: ``reduce_model`` on the paper bench.

Run:  .venv/bin/python benchmarks/bench_kalman_reduction.py [--repeat 3]

Balanced truncation of the fast model (1,474 nodes) for T1-T4 and D at condition I's operating
point, as ``feedtherm compensate`` builds it for its Kalman estimator
(analysis/compensation/state_space.py): wall time of each repeat in this process (the fast model
built once before, so only the reduction is timed), their median, the order and the five largest
Hankel singular values (which a change of the method's arithmetic must leave alone).
"""

from __future__ import annotations

import argparse
import statistics
import time

from feedtherm.analysis.compensation.state_space import reduce_model
from feedtherm.boundary.operating import OperatingPoint
from feedtherm.simulate import discretize
from feedtherm.system.load import load_system


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    loaded = load_system("paper")
    discretize(loaded.system, "fast")  # the network built (and kept) before the timed reductions
    point = OperatingPoint(1116.0, 1080.0, 293.15, 0.010)
    times = []
    for _ in range(args.repeat):
        started = time.perf_counter()
        model = reduce_model(loaded, ["T1", "T2", "T3", "T4", "D"], point)
        times.append(time.perf_counter() - started)
    print(f"reduce_model, paper bench: median {statistics.median(times):.2f} s of {[round(t, 2) for t in times]}; "
          f"order {model.order}; Hankel values {[round(float(h), 6) for h in model.hankel[:5]]}")


if __name__ == "__main__":
    main()
