#!/usr/bin/env python3
"""CalculiX deck of the peer block (../shared/notes/peers.md, "Explicit FE: CalculiX 2.20").

A 0.2 x 0.2 x 0.05 m block of NX x NY x NZ C3D8R elements, the thesis's tread Yeoh
rubber (C10, C20, C30; rho = 1178 kg/m^3; K0 = 20 mu0, mu0 = 2 C10, D1 = 2 / K0), bottom
fixed, top pushed down at 0.5 m/s (x, y held), *DYNAMIC, EXPLICIT for TIME seconds; ccx
picks its stable increment. The same block as bench/block_bench.cpp.
  calculix_block_deck.py NX NY NZ TIME [--trace]   (deck on stdout)
--trace prints the displacement of one top node at every increment (to count them).
"""
import sys

SIZE = (0.2, 0.2, 0.05)  # m
C10, C20, C30 = 0.777561e6, -0.276138e6, 0.095427e6  # Pa
DENSITY = 1178.0  # kg/m^3
D1 = 2.0 / (20.0 * 2.0 * C10)  # 1/Pa
# ccx's explicit Yeoh gives NaN unless D2 and D3 are set; 1/D2 = 1/D3 = 1 Pa is
# negligible beside K0 = 31.1 MPa.
D2 = D3 = 1.0
PUSH_SPEED = 0.5  # m/s


def deck(n, period, trace):
    nx, ny, nz = n

    def nid(i, j, k):
        return 1 + i + (nx + 1) * (j + (ny + 1) * k)

    out = ["*HEADING", f"peer block {nx} x {ny} x {nz} C3D8R, Yeoh tread", "*NODE, NSET=NALL"]
    for k in range(nz + 1):
        for j in range(ny + 1):
            for i in range(nx + 1):
                out.append(f"{nid(i, j, k)}, {SIZE[0] * i / nx:.9g}, {SIZE[1] * j / ny:.9g}, {SIZE[2] * k / nz:.9g}")
    out.append("*ELEMENT, TYPE=C3D8R, ELSET=EALL")
    e = 1
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                nodes = (nid(i, j, k), nid(i + 1, j, k), nid(i + 1, j + 1, k), nid(i, j + 1, k),
                         nid(i, j, k + 1), nid(i + 1, j, k + 1), nid(i + 1, j + 1, k + 1), nid(i, j + 1, k + 1))
                out.append(f"{e}, " + ", ".join(map(str, nodes)))
                e += 1
    for name, k in (("BOTTOM", 0), ("TOP", nz)):
        out.append(f"*NSET, NSET={name}")
        ids = [nid(i, j, k) for j in range(ny + 1) for i in range(nx + 1)]
        out += [", ".join(map(str, ids[a:a + 16])) for a in range(0, len(ids), 16)]
    out += ["*NSET, NSET=PROBE", str(nid(nx // 2, ny // 2, nz)),
            "*MATERIAL, NAME=TREAD", "*DENSITY", f"{DENSITY}",
            "*HYPERELASTIC, YEOH", f"{C10:.9g}, {C20:.9g}, {C30:.9g}, {D1:.9g}, {D2:.9g}, {D3:.9g}",
            "*SOLID SECTION, ELSET=EALL, MATERIAL=TREAD",
            "*BOUNDARY", "BOTTOM, 1, 3",
            # top z displacement = -0.5 m/s * t
            "*AMPLITUDE, NAME=PUSH", f"0., 0., 1., {-PUSH_SPEED}",
            "*STEP, INC=100000000", "*DYNAMIC, EXPLICIT", f"1.e-7, {period:.12g}",
            "*BOUNDARY", "TOP, 1, 2, 0.", "*BOUNDARY, AMPLITUDE=PUSH", "TOP, 3, 3, 1.",
            # printed at the end of the step: the total reaction on the top
            "*NODE PRINT, NSET=TOP, TOTALS=ONLY, FREQUENCY=100000000", "RF"]
    if trace:
        out += ["*NODE PRINT, NSET=PROBE, FREQUENCY=1", "U"]
    out.append("*END STEP")
    return "\n".join(out) + "\n"


if __name__ == "__main__":
    if len(sys.argv) not in (5, 6) or (len(sys.argv) == 6 and sys.argv[5] != "--trace"):
        sys.exit("usage: calculix_block_deck.py NX NY NZ TIME_S [--trace]")
    sys.stdout.write(deck(tuple(int(a) for a in sys.argv[1:4]), float(sys.argv[4]), len(sys.argv) == 6))
