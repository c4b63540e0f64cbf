#!/usr/bin/env python3
"""Curvature profile of a two-rope clasp VECT file (REFERENCE.md 6.3).

usage: bench/clasp_curvature.py CLASP.vect

Prints, per rope, kappa_i = 2 tan(theta_i / 2) / ebar at every interior
vertex (the curvature Rawdon's MinRad bounds), then the checks of 6.3:
congruence of the two ropes (largest profile difference), symmetry about
the tip, the shoulder S (mean of the first four vertices above 0.4, whose
period-2 zigzag averages out) and the kink K (largest curvature, at the
tip). Plain Python 3, no packages: run by hand, not by ctest."""
import math
import sys


def read_vect(path):
    nums = []
    with open(path) as f:
        for line in f:
            line = line.split("#", 1)[0].strip()
            if line and line != "VECT":
                nums.append([float(t) for t in line.split()])
    ncomp = int(nums[0][0])
    counts = [abs(int(v)) for v in nums[1]]
    pts = [r for r in nums[3:] if len(r) == 3]
    ropes, at = [], 0
    for n in counts[:ncomp]:
        ropes.append(pts[at:at + n])
        at += n
    return ropes


def curvature(rope):
    e = [[b[i] - a[i] for i in range(3)] for a, b in zip(rope, rope[1:])]
    length = [math.sqrt(sum(x * x for x in v)) for v in e]
    ebar = sum(length) / len(length)
    kap = []
    for (p, lp), (q, lq) in zip(zip(e, length), zip(e[1:], length[1:])):
        c = max(-1.0, min(1.0, sum(p[i] * q[i] for i in range(3)) / (lp * lq)))
        kap.append(2.0 * math.tan(0.5 * math.acos(c)) / ebar)
    return kap, ebar


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__.split("\n\n")[1])
    ropes = read_vect(sys.argv[1])
    if len(ropes) != 2:
        sys.exit("%s: want a clasp of two ropes, got %d components" % (sys.argv[1], len(ropes)))
    prof = []
    for k, rope in enumerate(ropes):
        kap, ebar = curvature(rope)
        prof.append(kap)
        print("rope %d: %d vertices, edge %.6f" % (k, len(rope), ebar))
        print("  " + " ".join("%.3f" % x for x in kap))
    a, b = prof
    if len(a) == len(b):
        print("congruence: max |kappa_A - kappa_B| = %.2e" % max(abs(x - y) for x, y in zip(a, b)))
    print("symmetry about the tip: max |kappa_A - reversed| = %.2e" % max(abs(x - y) for x, y in zip(a, a[::-1])))
    i0 = next((i for i, x in enumerate(a) if x > 0.4), None)
    if i0 is not None and i0 + 4 <= len(a):
        print("shoulder S: mean kappa of interior vertices %d..%d = %.4f (want 1/2)" % (i0 + 1, i0 + 4, sum(a[i0:i0 + 4]) / 4))
    imax = max(range(len(a)), key=lambda i: a[i])
    print("kink K: max kappa = %.6f at interior vertex %d of %d (want 1, at the tip)" % (a[imax], imax + 1, len(a) + 2))


if __name__ == "__main__":
    main()
