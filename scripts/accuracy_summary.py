"""Prints the summary of the accuracy table that docs/model.md section 9.2 shows.

Reads creep-core/data/accuracy.csv (written by `bash scripts/bench.sh --only accuracy`) and
prints, per preset and case, the cheapest grid and scheme whose largest F_x error is at most
1 % and the cheapest whose T_max rise error is also at most 3 %, each with its errors and
cost (wall time / simulated time, one thread), as a Markdown table.

    python3 scripts/accuracy_summary.py [creep-core/data/accuracy.csv]
"""

import csv
import sys


def cheapest(rows, ok):
    """The cheapest row that satisfies ok, or None."""
    good = [r for r in rows if ok(r)]
    return min(good, key=lambda r: float(r["wall_per_sim"])) if good else None


def cell(r):
    """One table cell: grid scheme, F_x / T rise error, cost."""
    if r is None:
        return "none"
    return (f"{r['nx']}x{r['ny']} {r['scheme']}: {float(r['fx_max_pct']):.2f} / "
            f"{float(r['trise_max_pct']):.2f} %, {float(r['wall_per_sim']):.2f}x")


def main():
    path = sys.argv[1] if len(sys.argv) > 1 else "creep-core/data/accuracy.csv"
    with open(path) as f:
        lines = [l for l in f if not l.startswith("#")]
    rows = list(csv.DictReader(lines))
    cases = []
    for r in rows:
        key = (r["preset"], r["kind"], r["v_m_s"], r["dt_ms"])
        if key not in cases:
            cases.append(key)
    print("| preset | case | limit's F_x uncertainty | F_x <= 1 % | F_x <= 1 % and T rise <= 3 % |")
    print("|---|---|---|---|---|")
    for key in cases:
        rs = [r for r in rows if (r["preset"], r["kind"], r["v_m_s"], r["dt_ms"]) == key]
        fx = cheapest(rs, lambda r: float(r["fx_max_pct"]) <= 1.0)
        both = cheapest(rs, lambda r: float(r["fx_max_pct"]) <= 1.0
                        and float(r["trise_max_pct"]) <= 3.0)
        preset, kind, v, dt = key
        print(f"| {preset} | {kind}, {v} m/s, {dt} ms | {float(rs[0]['fx_limit_unc_pct']):.3f} % "
              f"| {cell(fx)} | {cell(both)} |")


if __name__ == "__main__":
    main()
