#!/usr/bin/env python3
"""The thin-layer bearing check (docs/validation.md, "A thin layer that bears").

A rigid rough strip (B = 0.2 m) pushed into a cohesive frictionless layer of
depth H on a rigid base, H/B = 0.4, 0.5 and 1, by the SPH terrain
(configs/scenes/strip_bearing.textproto) at several particle counts through H
and by the plane-strain Lagrangian FE (strip_bearing_fe) at two mesh sizes,
against the closed forms of tests/snow_fe/thin_layer_bearing_factors.csv.
Bases: smooth and free to spread (the layer ends 0.1 m short of the box's
wall), smooth and confined (the layer fills the box, as the rolling scenes'
snow does), rough (the box's floor no-slip: runs once the container's floor
takes a contact law; skipped, and said so, before).

Writes <out>/strip_bearing.csv (one row per case), <out>/strip_bearing.md (the
table) and <out>/strip_bearing.png (N_c against H/B). Each SPH run is
single-threaded (small runs are faster so on a shared machine) under nice.

    scripts/strip_bearing_study.py --build build --out out/strip_bearing
"""
import argparse
import csv
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENE = os.path.join(ROOT, "configs/scenes/strip_bearing.textproto")
FACTORS = os.path.join(ROOT, "tests/snow_fe/thin_layer_bearing_factors.csv")
B = 0.2            # the scene's strip width [m]
LAYER_LENGTH = 0.6  # the layer's x-length from the centre line [m]
GAP = 0.1          # the free end's gap to the box's wall [m]
SHEAR_STRENGTH = 10e3  # c = d / sqrt(3) of the scene's snow [Pa]
ROUGH_FLOOR = "sph.container.floor.kind=NO_SLIP"


def limit_pressure(d, p):
    """The largest pressure up to a settlement of B/40 (snow_fe::limit_pressure_Pa)."""
    return max(y for x, y in zip(d, p) if x <= B / 40)


def layer_sets(h_over_b, base, spacing):
    H = h_over_b * B
    width = 3 * spacing  # the plane-strain slab: three particles in y
    box_x = LAYER_LENGTH + (GAP if base == "smooth_free" else 0.0)
    sets = [f"sph.particle_spacing_m={spacing!r}",
            f"sph.container.max.x={box_x!r}", f"sph.container.max.y={width!r}", f"sph.container.max.z={H!r}",
            f"sph.blocks[0].region.max.y={width!r}", f"sph.blocks[0].region.max.z={H!r}",
            f"sph.rigid_bodies[0].initial_bottom_centre_m.y={0.5 * width!r}",
            f"sph.rigid_bodies[0].initial_bottom_centre_m.z={H!r}"]
    if base == "rough":
        sets.append(ROUGH_FLOOR)
    return sets, width


def run_sph(build, out, h_over_b, base, particles):
    spacing = h_over_b * B / particles
    sets, width = layer_sets(h_over_b, base, spacing)
    folder = os.path.join(out, f"sph_{base}_hb{h_over_b}_n{particles}")
    args = [os.path.join(build, "bin/snow_sph"), SCENE, "--quiet", "--no-vtk", "--out", folder]
    for s in sets:
        args += ["--set", s]
    check = subprocess.run(args[:2] + ["--check"] + args[6:], capture_output=True, text=True)
    if check.returncode != 0:
        return None, check.stderr.strip().splitlines()[-1]
    env = dict(os.environ, OMP_NUM_THREADS="1")
    subprocess.run(["nice", "-n", "5"] + args, check=True, env=env, capture_output=True)
    d, p = [], []
    with open(os.path.join(folder, "bodies.csv")) as f:
        for row in csv.DictReader(f):
            d.append(float(row["strip_displacement_m"]))
            p.append(float(row["strip_contact_force_z_N"]) / (0.5 * B * width))
    keep = [(x, y) for x, y in zip(d, p) if x > 0]
    return ([x for x, _ in keep], [y for _, y in keep]), ""


def run_fe(build, out, h_over_b, base, elements):
    sets, _ = layer_sets(h_over_b, base, h_over_b * B / 6)
    path = os.path.join(out, f"fe_{base}_hb{h_over_b}_e{elements}.csv")
    args = ["nice", "-n", "5", os.path.join(build, "bin/strip_bearing_fe"), SCENE, "--out", path,
            "--base", "rough" if base == "rough" else "smooth", "--elements-per-width", str(elements)]
    if base == "smooth_free":
        args.append("--free-end")
    for s in sets:
        if s != ROUGH_FLOOR:
            args += ["--set", s]
    subprocess.run(args, check=True, capture_output=True)
    d, p = [], []
    with open(path) as f:
        for row in csv.DictReader(f):
            d.append(float(row["displacement_m"])), p.append(float(row["pressure_Pa"]))
    return d, p


def closed_forms():
    rows = []
    with open(FACTORS) as f:
        for row in csv.DictReader(r for r in f if not r.startswith("#")):
            rows.append(row)
    return rows


def write_plot(out, rows):
    """N_c against H/B: the finest run of each method and base as markers, the closed forms as lines."""
    plots = []
    for k, (method, base, title) in enumerate([
            ("SPH", "smooth_free", "SPH, smooth base, free to spread"), ("SPH", "smooth_confined", "SPH, smooth base, confined"),
            ("SPH", "rough", "SPH, rough base"), ("FE", "smooth_free", "FE, smooth base, free to spread"),
            ("FE", "smooth_confined", "FE, smooth base, confined"), ("FE", "rough", "FE, rough base")]):
        points = [r for r in rows if r["method"] == method and r["base"] == base and r["finest"] == "yes"]
        if not points:
            continue
        data = os.path.join(out, f"strip_bearing_{method}_{base}.dat")
        with open(data, "w") as f:
            f.writelines(f"{r['H_over_B']} {r['N_c']}\n" for r in points)
        plots.append(f"'{data}' using 1:2 with points pt {5 if method == 'SPH' else 7} ps 1.6 lc {k % 3 + 1} "
                     f"title '{title} (finest)'")
    # The closed forms (tests/snow_fe/thin_layer_bearing_factors.csv): 2 + pi, exact on a rough base
    # for H/B >= 0.707 and its lower bound below; 2, exact on a smooth base free to spread at H/B = 0.5
    # and its lower bound at every depth.
    plots.append("5.1416 with lines lw 2 lc 3 dt 2 title 'rough base: 2 + {/Symbol p} (exact for H/B >= 0.71, lower bound below)'")
    plots.append("2.0 with lines lw 2 lc 1 dt 2 title 'smooth base, free: 2 (exact at H/B = 0.5, lower bound elsewhere)'")
    png = os.path.join(out, "strip_bearing.png")
    script = "\n".join([
        "set terminal pngcairo size 900,700", f"set output '{png}'",
        "set title 'Rigid rough strip on a Tresca layer over a rigid base: N_c = q_u / c (largest up to B/40)'",
        "set xlabel 'H / B'", "set ylabel 'q_u / c'", "set xrange [0.3:1.1]", "set yrange [0:10]",
        "set key top left", "set grid", "plot " + ", \\\n  ".join(plots)])
    subprocess.run(["gnuplot"], input=script, text=True, check=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default="build")
    ap.add_argument("--out", default="out/strip_bearing")
    ap.add_argument("--depths", default="0.4,0.5,1")
    ap.add_argument("--particles", default="4,6,10", help="SPH particles through H")
    ap.add_argument("--elements", default="10,20", help="FE elements across B")
    ap.add_argument("--bases", default="smooth_free,smooth_confined,rough")
    ap.add_argument("--replot", action="store_true", help="only redraw the plot from <out>/strip_bearing.csv")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    if a.replot:
        with open(os.path.join(a.out, "strip_bearing.csv")) as f:
            write_plot(a.out, list(csv.DictReader(f)))
        return 0
    depths = [float(x) for x in a.depths.split(",")]
    particles = [int(x) for x in a.particles.split(",") if x]
    elements = [int(x) for x in a.elements.split(",") if x]
    rows, notes = [], []
    for base in a.bases.split(","):
        for hb in depths:
            for n in particles:
                curve, why = run_sph(a.build, a.out, hb, base, n)
                if curve is None:
                    notes.append(f"SPH {base} H/B {hb} n {n}: not run ({why})")
                    continue
                d, p = curve
                rows.append({"method": "SPH", "base": base, "H_over_B": hb, "resolution": f"{n} particles through H",
                             "N_c": round(limit_pressure(d, p) / SHEAR_STRENGTH, 3),
                             "at_B_over_20": round(p[-1] / SHEAR_STRENGTH, 3), "finest": "yes" if n == particles[-1] else "no"})
                print(rows[-1], flush=True)
            for e in elements:
                d, p = run_fe(a.build, a.out, hb, base, e)
                rows.append({"method": "FE", "base": base, "H_over_B": hb, "resolution": f"{e} elements across B",
                             "N_c": round(limit_pressure(d, p) / SHEAR_STRENGTH, 3),
                             "at_B_over_20": round(p[-1] / SHEAR_STRENGTH, 3), "finest": "yes" if e == elements[-1] else "no"})
                print(rows[-1], flush=True)
    with open(os.path.join(a.out, "strip_bearing.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader(), w.writerows(rows)
    refs = {}
    for r in closed_forms():
        key = (r["base"], float(r["H_over_B"]))
        refs[key] = (refs[key] + ", " if key in refs else "") + f"{r['N_c']} ({r['kind']})"
    with open(os.path.join(a.out, "strip_bearing.md"), "w") as f:
        f.write("| base | H/B | method | resolution | N_c (largest q/c up to B/40) | q/c at B/20 | closed form |\n|---|---|---|---|---|---|---|\n")
        for r in rows:
            ref_text = refs.get((r["base"], r["H_over_B"]), "-")
            f.write(f"| {r['base']} | {r['H_over_B']} | {r['method']} | {r['resolution']} | {r['N_c']} | "
                    f"{r['at_B_over_20']} | {ref_text} |\n")
        for n in notes:
            f.write(f"\n{n}\n")
    write_plot(a.out, rows)
    for n in notes:
        print(n)
    return 0


if __name__ == "__main__":
    sys.exit(main())
