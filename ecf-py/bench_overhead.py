"""Per-call overhead of the Python package ecf against the `ecf` command line (a benchmark, not a test).

Times, in one run: a 1,000-point curve as one `ecf.curve` call and as one `ecf curve` process
(CSV written and parsed), and the overhead of one `ecf.curve` call (1,000 calls of one point
against the 1,000-point call, per point). Usage:

    python ecf-py/bench_overhead.py [--ecf target/release/ecf] [--preset dry] [--grid 40x11]
"""

import argparse
import os
import subprocess
import time
from pathlib import Path

import numpy as np

import ecf


def best(f, repeat):
    """The shortest of `repeat` runs of f(), s."""
    t = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        f()
        t.append(time.perf_counter() - t0)
    return min(t)


def main():
    root = Path(__file__).resolve().parents[1]
    target = Path(os.environ.get("CARGO_TARGET_DIR", root / "target"))
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--ecf", default=str(target / "release" / "ecf"), help="the ecf binary")
    ap.add_argument("--preset", default="dry")
    ap.add_argument("--grid", default="40x11", help="bristle grid NXxNY")
    ap.add_argument("--repeat", type=int, default=3, help="runs of each; the shortest counts")
    a = ap.parse_args()
    n = 1000
    cx = np.linspace(0.001, 0.3, n)
    kw = dict(preset=a.preset, grid=a.grid)

    def py_curve():
        return ecf.curve(cx=cx, **kw)

    def cli_curve():
        out = subprocess.run(
            [a.ecf, "curve", "--preset", a.preset, "--grid", a.grid, "--cx", f"0.001:0.3:{n}"],
            capture_output=True, text=True, check=True,
        ).stdout
        return np.loadtxt(out.splitlines()[1:], delimiter=",")

    t_py = best(py_curve, a.repeat)
    t_cli = best(cli_curve, a.repeat)
    # one point per call: the overhead is what a call costs beyond its point
    one = [np.array([c]) for c in cx]
    t_single = best(lambda: [ecf.curve(cx=c, **kw) for c in one], a.repeat)
    per_point = t_py / n
    overhead = t_single / n - per_point
    # the same for the cheapest model (Polach's closed form): the call's cost nearly alone
    t_pol = best(lambda: ecf.curve(cx=cx, model="polach"), a.repeat)
    t_pol1 = best(lambda: [ecf.curve(cx=c, model="polach") for c in one], a.repeat)
    print(f"{n}-point curve, {a.preset} {a.grid}:")
    print(f"  ecf.curve (one call)      {t_py * 1e3:9.2f} ms ({per_point * 1e6:.1f} us per point)")
    print(f"  ecf curve (one process)   {t_cli * 1e3:9.2f} ms (process start, CSV out and parsed)")
    print(f"  {n} calls of one point    {t_single * 1e3:9.2f} ms: overhead {overhead * 1e6:.1f} us per call "
          f"({100 * overhead / per_point:.1f} % of one point)")
    print(f"polach (closed form): {n} points in one call {t_pol * 1e3:.2f} ms, in {n} calls {t_pol1 * 1e3:.2f} ms: "
          f"{(t_pol1 - t_pol) / n * 1e6:.1f} us per call")


if __name__ == "__main__":
    main()
