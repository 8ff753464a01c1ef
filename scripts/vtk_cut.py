#!/usr/bin/env python3
"""A vertical cut through a particle frame (snow_sph's legacy binary VTK) as a PNG.

    scripts/vtk_cut.py FRAME.vtk OUT.png [--y 0.0] [--width 0.01] [--title TEXT]

Takes the particles within --width of the plane y = --y (the plate's symmetry
plane in the plate-sinkage scene) and draws, side by side, their von Mises
stress, the cap's hydrostatic yield pressure p_b and the volumetric plastic
strain in the x-z plane, with gnuplot (pngcairo). Standard library only.
"""
import argparse
import os
import struct
import subprocess
import sys
import tempfile


def read_frame(path):
    """Points and point fields of a legacy binary POLYDATA file (big-endian floats)."""
    data = open(path, "rb").read()
    pos, fields, n = 0, {}, 0

    def line():
        nonlocal pos
        end = data.index(b"\n", pos)
        text = data[pos:end].decode("ascii", "replace").strip()
        pos = end + 1
        return text

    while pos < len(data):
        text = line()
        words = text.split()
        if not words:
            continue
        if words[0] == "POINTS":
            n = int(words[1])
            fields["points"] = struct.unpack(">%df" % (3 * n), data[pos:pos + 12 * n])
            pos += 12 * n
        elif words[0] == "VERTICES":
            size = int(words[2])
            pos += 4 * size
        elif words[0] == "SCALARS":
            if line().split()[0] != "LOOKUP_TABLE":
                raise ValueError(path + ": SCALARS without LOOKUP_TABLE")
            fields[words[1]] = struct.unpack(">%df" % n, data[pos:pos + 4 * n])
            pos += 4 * n
        elif words[0] == "VECTORS":
            fields[words[1]] = struct.unpack(">%df" % (3 * n), data[pos:pos + 12 * n])
            pos += 12 * n
    return n, fields


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("frame")
    ap.add_argument("png")
    ap.add_argument("--y", type=float, default=0.0)
    ap.add_argument("--width", type=float, default=0.01)
    ap.add_argument("--title", default="")
    a = ap.parse_args()
    n, f = read_frame(a.frame)
    p = f["points"]
    rows = []
    for i in range(n):
        x, y, z = p[3 * i], p[3 * i + 1], p[3 * i + 2]
        if abs(y - a.y) <= a.width:
            rows.append((x, z, f["von_mises_stress_Pa"][i] / 1e3, f["cap_hydrostatic_yield_pressure_Pa"][i] / 1e3,
                         f["volumetric_plastic_strain"][i]))
    if not rows:
        sys.exit("%s: no particle within %g m of y = %g" % (a.frame, a.width, a.y))
    with tempfile.NamedTemporaryFile("w", suffix=".dat", delete=False) as t:
        for r in rows:
            t.write("%g %g %g %g %g\n" % r)
    panels = [(3, "von Mises stress [kPa]"), (4, "cap yield pressure p_b [kPa]"), (5, "volumetric plastic strain")]
    script = ['set terminal pngcairo size 1500,520 font ",10"', 'set output "%s"' % a.png,
              'set multiplot layout 1,3 title "%s"' % a.title.replace('"', "'"),
              "set size ratio -1", "set xlabel 'x [m]'", "set ylabel 'z [m]'", "set palette rgb 33,13,10"]
    for col, label in panels:
        script += ['set title "%s"' % label, "plot '%s' using 1:2:%d with points pt 7 ps 0.6 lc palette notitle" % (t.name, col)]
    script.append("unset multiplot")
    subprocess.run(["gnuplot"], input="\n".join(script), text=True, check=True)
    os.unlink(t.name)
    print("%s: %d particles within %g m of y = %g" % (a.png, len(rows), a.width, a.y))


if __name__ == "__main__":
    main()
