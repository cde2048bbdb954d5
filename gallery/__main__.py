"""python -m gallery [--quick] [--no-plots] [--jobs N] [--only KEY,...] OUTDIR

Computes every gallery figure with the project's programs, evaluates the seed's statements,
writes OUTDIR/*.png, OUTDIR/numbers.json and OUTDIR/README.md. Exit code 1 when an assertion
has an unexpected outcome or a figure fails (drive-train figures are marked pending instead
when the drive-train demo cannot run). Expects the binaries built (scripts/gallery.sh does it)."""
from __future__ import annotations

import argparse
import json
import sys
import time
import traceback
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from . import readme, run
from .core import FULL, QUICK, clean
from .registry import FIGURES, MAY_BE_PENDING


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m gallery", description=__doc__.split("\n\n")[1])
    ap.add_argument("outdir", type=Path)
    ap.add_argument("--quick", action="store_true", help="reduced settings (coarser grids, fewer points), every figure and assertion")
    ap.add_argument("--no-plots", action="store_true", help="numbers.json and README.md only")
    ap.add_argument("--jobs", type=int, default=2, help="figures computed in parallel (each runs one process at a time) [2]")
    ap.add_argument("--only", default="", help="comma-separated figure keys (for development)")
    a = ap.parse_args(argv)
    S = dict(QUICK if a.quick else FULL)
    figs = [F for F in FIGURES if not a.only or F.key in a.only.split(",")]
    for b in (run.ECF,):
        if not b.exists():
            print(f"gallery: {b} not found; build it first (scripts/gallery.sh does)", file=sys.stderr)
            return 2
    t0 = time.time()
    results = {}

    def work(F):
        t = time.time()
        try:
            n, data = F.compute(S)
            return F.key, ("ok", clean(n), data, time.time() - t)
        except Exception as e:  # noqa: BLE001 - reported per figure
            return F.key, ("error", f"{type(e).__name__}: {e}", traceback.format_exc(), time.time() - t)

    # the slow drive-train group first, so that the two workers finish together
    order = sorted(figs, key=lambda F: F.key not in MAY_BE_PENDING)
    with ThreadPoolExecutor(max_workers=max(1, a.jobs)) as ex:
        for key, r in ex.map(work, order):
            results[key] = r
            print(f"gallery: computed {key} ({r[0]}, {r[3]:.1f} s)", file=sys.stderr, flush=True)
    doc = {"settings": S, "figures": {}}
    bad = []
    a.outdir.mkdir(parents=True, exist_ok=True)
    for F in figs:
        st, n, data, dt = results[F.key]
        if st != "ok":
            if F.key in MAY_BE_PENDING:
                doc["figures"][F.key] = {"status": "pending", "reason": f"the drive-train demo could not be run by the gallery ({n.splitlines()[0][:300]}); the gallery calls `python -m drivetrain_demo step|ramp|sine` and will show these figures once it runs.", "pngs": []}
                print(f"gallery: {F.key} pending: {n}", file=sys.stderr)
                continue
            print(data, file=sys.stderr)
            bad.append(f"{F.key}: {n}")
            continue
        checks = F.checks(n, S)
        pngs = [] if a.no_plots else F.plot(n, data, a.outdir, S)
        if not a.no_plots and sorted(pngs) != sorted(F.pngs):
            bad.append(f"{F.key}: wrote {pngs}, registry lists {F.pngs}")
        doc["figures"][F.key] = {"status": "ok", "pngs": list(F.pngs), "numbers": n, "checks": [c.as_dict() for c in checks]}
        for c in checks:
            if c.passed != c.expected:
                bad.append(f"{F.key}/{c.id}: passed={c.passed}, expected={c.expected}: {c.measured}")
    doc = clean(doc)
    (a.outdir / "numbers.json").write_text(json.dumps(doc, indent=1) + "\n")
    (a.outdir / "README.md").write_text(readme.render(doc))
    el = time.time() - t0
    (a.outdir / "run_info.txt").write_text(f"mode {S['mode']}\nrun time {el:.1f} s\ncommit {run.git_describe()}\n")
    n_checks = sum(len(v.get("checks", [])) for v in doc["figures"].values())
    print(f"gallery: {len(doc['figures'])} figure groups, {n_checks} assertions, {len(bad)} problems, {el:.1f} s -> {a.outdir}", file=sys.stderr)
    for b in bad:
        print(f"gallery: PROBLEM {b}", file=sys.stderr)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
