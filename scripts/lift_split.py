#!/usr/bin/env python3
"""Where the water lifts a tyre: the coupler's F4 split, against the speed, as CSV and PNG.

    scripts/lift_split.py RUN_DIR OUT_PREFIX [--mean-s 0.005] [--title TEXT]

Reads RUN_DIR/coupler/forces.csv (a coupled run; the columns
vertical_pressure_force_N, vertical_pressure_force_tread_top_N and
vertical_pressure_force_groove_N) and writes OUT_PREFIX.csv and OUT_PREFIX.png:
the terrain's vertical pressure force on the tyre F4, its part on the tread tops,
its part in the pattern's recesses (groove walls and floors, sipe walls) and the
rest (shoulders, sidewalls), each a centred moving mean over --mean-s (5 ms, the
hydroplaning reading's filter, tyre_fe/hydroplaning.hpp), against the rim's
forward speed (the rim's x differenced over the same span). Standard library
and gnuplot (pngcairo) only.
"""
import argparse
import bisect
import csv
import os
import subprocess
import sys


def read_forces(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    need = ["time_s", "rim_x_m", "vertical_pressure_force_N", "vertical_pressure_force_tread_top_N",
            "vertical_pressure_force_groove_N"]
    if not rows:
        sys.exit(f"{path}: no rows")
    missing = [c for c in need if c not in rows[0]]
    if missing:
        sys.exit(f"{path}, line 1: no column {', '.join(missing)} (a run before the coupler split F4)")
    return {c: [float(r[c]) for r in rows] for c in need}


def prefix_sums(v):
    out = [0.0]
    for x in v:
        out.append(out[-1] + x)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run_dir")
    ap.add_argument("out_prefix")
    ap.add_argument("--mean-s", type=float, default=0.005)
    ap.add_argument("--title", default="Water's vertical force on the tyre, by where it acts")
    a = ap.parse_args()
    f = read_forces(os.path.join(a.run_dir, "coupler", "forces.csv"))
    t, x = f["time_s"], f["rim_x_m"]
    f4, top, groove = (f["vertical_pressure_force_N"], f["vertical_pressure_force_tread_top_N"],
                       f["vertical_pressure_force_groove_N"])
    rest = [a_ - b - c for a_, b, c in zip(f4, top, groove)]
    sums = [prefix_sums(v) for v in (f4, top, groove, rest)]
    csv_path = a.out_prefix + ".csv"
    with open(csv_path, "w") as out:
        out.write("time_s,speed_m_per_s,vertical_pressure_force_N,tread_top_N,groove_N,rest_N\n")
        step = max(1, len(t) // 2000)  # about 2,000 rows
        for i in range(0, len(t), step):
            # The rows within [t - span/2, t + span/2]: first and one past the last.
            first = bisect.bisect_left(t, t[i] - 0.5 * a.mean_s)
            end = bisect.bisect_right(t, t[i] + 0.5 * a.mean_s)
            last = end - 1
            speed = (x[last] - x[first]) / (t[last] - t[first]) if t[last] > t[first] else 0.0
            means = [(p[end] - p[first]) / (end - first) for p in sums]
            out.write(f"{t[i]:.6f},{speed:.4f}," + ",".join(f"{m:.2f}" for m in means) + "\n")
    script = f"""set terminal pngcairo size 1000,600 font ',11'
set output '{a.out_prefix}.png'
set datafile separator ','
set title "{a.title}"
set xlabel 'forward speed [m/s]'
set ylabel 'vertical force on the tyre [N] ({1e3 * a.mean_s:g} ms mean)'
set key top left
set grid
plot '{csv_path}' every ::1 using 2:3 with lines lw 2 title 'all (F4)', \\
     '' every ::1 using 2:4 with lines lw 2 title 'tread tops', \\
     '' every ::1 using 2:5 with lines lw 2 title 'grooves and sipes', \\
     '' every ::1 using 2:6 with lines lw 1 title 'shoulders, sidewalls'
"""
    subprocess.run(["gnuplot"], input=script, text=True, check=True)
    print(f"wrote {csv_path} and {a.out_prefix}.png")


if __name__ == "__main__":
    main()
