#!/usr/bin/env python3
"""The trefoil's fine numbers against N (issue 23 item 2), as a Markdown table.

    bench/shape_table.py OUTDIR CURVE_N1 [CURVE_N2 ...]

For each curve (the ladder's OUTDIR/final_N.vect from bench/extrapolate_trefoil.sh)
runs `tightrope analyze CURVE --out OUTDIR/shape_N -m 1 --strut-tol T` for T in 1e-7
(the main run), 1e-6 and 1e-9, and prints l1, l2, Delta kappa_1,2, Delta alpha_1,2
with analyze's uncertainties, and the two 9-cycles: their points from the main run,
each with the largest change over the other strut tolerances as its uncertainty (the
contact set's width: 1e-4, the default for the engine's looser curves, smears the
converged solver's contacts over 0.03 of arclength), and the D3 spread of the
reduced cycle classes. Beside them the paper's values (REFERENCE.md 5.3-5.4).
Environment: BUILD (default build).
"""
import json
import os
import subprocess
import sys

PAPER = {
    "l1": (0.158, 0.001), "l2": (0.319, 0.001),
    "dkappa1": (0.264, 0.005), "dkappa2": (0.115, 0.005),
    "dalpha1": (0.159, 0.005), "dalpha2": (0.062, 0.005),
}
C9M = [0.189, 15.674, 32.370, 11.103, 26.588, 10.541, 22.018, 4.759, 21.455]
C9P = [32.554, 11.288, 27.984, 10.725, 22.202, 6.155, 21.640, 0.373, 17.069]
TOLS = ["1e-7", "1e-6", "1e-9"]


def analyze(tr, curve, out, tol):
    subprocess.run([tr, "analyze", curve, "--out", out, "-m", "1", "--strut-tol", tol],
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)


def cycle(summary, stable):
    for c in summary["contacts"].get("cycles", []):
        if c["period"] == 9 and c["stable"] == stable:
            return c
    return None


def match(members, paper):
    """Our cycle's points in the paper's order: each paper point's nearest member
    (cyclic distance on the knot of length ~32.743)."""
    L = 32.742934
    out = []
    for p in paper:
        best = min(members, key=lambda m: abs((m - p + L / 2) % L - L / 2))
        out.append(best)
    return out


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    tr = os.path.join(os.environ.get("BUILD", os.path.join(here, "build")), "tightrope")
    outdir = sys.argv[1]
    cols = []
    for curve in sys.argv[2:]:
        runs = {}
        for tol in TOLS:
            name = os.path.splitext(os.path.basename(curve))[0]
            runs[tol] = analyze(tr, curve, os.path.join(outdir, "shape_%s_tol%s" % (name, tol)), tol)
        main_run = runs[TOLS[0]]
        rl = main_run["ropelength"]
        col = {"N": main_run["vertices"], "ropelength": rl.get("ropelength") if isinstance(rl, dict) else rl}
        pl = main_run["plateaus"]
        col["l1"] = (pl.get("l1"), pl.get("l1_err"))
        col["l2"] = (pl.get("l2"), pl.get("l2_err"))
        col["plateaus"] = pl.get("count")
        j = main_run["jumps"]
        for k in ("dkappa1", "dkappa2", "dalpha1", "dalpha2"):
            v = j.get(k, {})
            col[k] = (v.get("value"), v.get("err")) if isinstance(v, dict) else (None, None)
        for stable, paper, key in ((1, C9M, "C9-"), (0, C9P, "C9+")):
            c = cycle(main_run, stable)
            if not c:
                col[key] = None
                continue
            pts = match(c["members"], paper)
            errs = [0.0] * 9
            for tol in TOLS[1:]:
                other = cycle(runs[tol], stable)
                if not other:
                    errs = [float("nan")] * 9
                    break
                opts = match(other["members"], paper)
                errs = [max(e, abs(a - b)) for e, a, b in zip(errs, pts, opts)]
            red = sorted(c["reduced"])
            classes = [red[0:3], red[3:6], red[6:9]]
            col[key] = (pts, errs, [(sum(g) / 3, max(g) - min(g)) for g in classes])
        col["fixed"] = main_run["contacts"].get("fixed_points")
        cols.append(col)

    def f(v, e=None, d=4):
        if v is None:
            return "n/a"
        return ("%.*f" % (d, v)) + ("" if e is None else " +- %.*f" % (d, e))

    hdr = "| quantity | " + " | ".join("N = %d" % c["N"] for c in cols) + " | paper |"
    print(hdr)
    print("|" + "---|" * (len(cols) + 2))
    print("| plateaus found | " + " | ".join(str(c["plateaus"]) for c in cols) + " | 6 |")
    for k, name in (("l1", "l1"), ("l2", "l2"), ("dkappa1", "Delta kappa_1"), ("dkappa2", "Delta kappa_2"),
                    ("dalpha1", "Delta alpha_1"), ("dalpha2", "Delta alpha_2")):
        print("| %s | " % name + " | ".join(f(*c[k]) for c in cols) + " | %s |" % f(*PAPER[k], d=3))
    print("| fixed points of sigma-^9 | " + " | ".join(str(c["fixed"]) for c in cols) + " | 18 |")
    for key, paper in (("C9-", C9M), ("C9+", C9P)):
        for i, p in enumerate(paper):
            row = []
            for c in cols:
                if not c[key]:
                    row.append("n/a")
                else:
                    row.append(f(c[key][0][i], c[key][1][i], 3))
            print("| %s point %d | " % (key, i + 1) + " | ".join(row) + " | %.3f |" % p)
        row = []
        for c in cols:
            if not c[key]:
                row.append("n/a")
            else:
                row.append(", ".join("%.4f (%.0e)" % g for g in c[key][2]))
        print("| %s reduced classes (D3 spread) | " % key + " | ".join(row) + " | %s |"
              % ("0.189, 0.373, 4.759" if key == "C9-" else "0.189, 0.373, 4.759"))
    # the largest distance of any cycle point from the paper's, per N
    row = []
    for c in cols:
        d = 0.0
        for key, paper in (("C9-", C9M), ("C9+", C9P)):
            if c[key]:
                d = max([d] + [abs(a - b) for a, b in zip(c[key][0], paper)])
        row.append("%.4f" % d)
    print("| max \\|cycle point - paper\\| | " + " | ".join(row) + " | |")


if __name__ == "__main__":
    main()
