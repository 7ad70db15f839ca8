# SPDX-License-Identifier: GPL-3.0-or-later
"""Helpers of bench/openfoam_cylinder.sh (pure Python 3, no numpy).

  openfoam_cylinder.py inlet CASE UM         inlet U values (face average of the parabola)
  openfoam_cylinder.py steady CASE UM TIME   cD, cL (forces function object and own wall
                                             extrapolation), pressure / viscous split, dp
  openfoam_cylinder.py shedding CASE UM      St, cD max / mean / min, cL max / min
"""
import glob
import math
import os
import re
import sys

H, D, CX, CY, NU = 0.41, 0.1, 0.2, 0.2, 1e-3

NUM = r"[-+0-9.eE]+"


def foam_list(text, start):
    """The list following position `start`: N ( ... ) of scalars or (x y z) vectors."""
    m = re.compile(r"(\d+)\s*\(").search(text, start)
    n = int(m.group(1))
    body_start = m.end()
    depth, i = 1, body_start
    while depth:
        c = text[i]
        depth += c == "("
        depth -= c == ")"
        i += 1
    body = text[body_start:i - 1]
    if "(" in body:
        vals = [tuple(float(v) for v in t.split()) for t in re.findall(r"\(([^()]*)\)", body)]
    else:
        vals = [float(v) for v in body.split()]
    assert len(vals) == n, (len(vals), n)
    return vals


def strip_header(text):
    return re.sub(r"FoamFile\s*\{[^}]*\}", "", re.sub(r"//.*", "", text), count=1)


def read_list(path):
    return foam_list(strip_header(open(path).read()), 0)


def faces_of(path):
    text = strip_header(open(path).read())
    m = re.compile(r"(\d+)\s*\(").search(text)
    return [tuple(int(v) for v in f.split()) for f in re.findall(r"\d+\(([^()]*)\)", text[m.end():])]


def boundary(case):
    text = strip_header(open(f"{case}/constant/polyMesh/boundary").read())
    out = {}
    for name, body in re.findall(r"(\w+)\s*\{([^}]*)\}", text):
        out[name] = (int(re.search(r"startFace\s+(\d+)", body).group(1)),
                     int(re.search(r"nFaces\s+(\d+)", body).group(1)))
    return out


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def patch_faces(case, name):
    """Centres and area vectors (out of the domain) of a patch's quads."""
    pts = read_list(f"{case}/constant/polyMesh/points")
    faces = faces_of(f"{case}/constant/polyMesh/faces")
    start, n = boundary(case)[name]
    out = []
    for f in faces[start:start + n]:
        p = [pts[i] for i in f]
        c = tuple(sum(x[k] for x in p) / len(p) for k in range(3))
        s = tuple(0.5 * v for v in cross(sub(p[2], p[0]), sub(p[3], p[1])))
        out.append((c, s))
    return out, start


def thickness(case):
    pts = read_list(f"{case}/constant/polyMesh/points")
    return max(p[2] for p in pts) - min(p[2] for p in pts)


def inlet(case, um):
    vals = []
    for c, s in patch_faces(case, "inlet")[0]:
        y = c[1]
        h = math.sqrt(dot(s, s)) / thickness(case)
        vals.append(4 * um * (y * (H - y) - h * h / 12) / (H * H))
    print(f"nonuniform List<vector> {len(vals)} (" + " ".join(f"({v:.17g} 0 0)" for v in vals) + ")")


def internal(path):
    text = strip_header(open(path).read())
    return foam_list(text, text.index("internalField"))


def series(path):
    """Rows of numbers of a function object's .dat file (brackets dropped)."""
    rows = []
    for line in open(path):
        if line.startswith("#") or not line.strip():
            continue
        rows.append([float(v) for v in re.findall(NUM, line.replace("(", " ").replace(")", " "))])
    return rows


def fo_file(case, fo, name):
    files = sorted(glob.glob(f"{case}/postProcessing/{fo}/*/{name}"),
                   key=lambda p: float(p.split("/")[-2]))
    return files


def steady(case, um, time, verbose=True):
    ubar = 2 * um / 3
    tz = thickness(case)
    q = 0.5 * ubar * ubar * D * tz
    # Forces function object (v1912: force.dat columns time, total xyz, pressure xyz, viscous xyz).
    frows = []
    for f in fo_file(case, "forces", "force.dat"):
        frows += series(f)
    row = min(frows, key=lambda r: abs(r[0] - float(time)))
    tot, pre, vis = row[1:4], row[4:7], row[7:10]
    fo = (tot[0] / q, tot[1] / q)
    if verbose:
        print(f"forces FO:     cD {tot[0] / q:.5f} (pressure {pre[0] / q:.5f}, "
              f"viscous {vis[0] / q:.5f})  cL {tot[1] / q:.5f} (pressure {pre[1] / q:.5f}, "
              f"viscous {vis[1] / q:.5f})")
    # Two-cell wall stencil on the same field (auvloop's force evaluation before session 4; its dp
    # evaluation still, engine/src/validation/wall_stencil.hpp):
    # each wall face sees its cell P and the neighbour Q of P furthest along the normal; values
    # moved onto the normal with their cell gradients; dU/dn from the parabola through U_wall = 0,
    # U_P, U_Q and p_wall by linear extrapolation of p_P and p_Q.
    t = time
    p = internal(f"{case}/{t}/p")
    U = internal(f"{case}/{t}/U")
    gp = internal(f"{case}/{t}/grad(p)")
    gU = internal(f"{case}/{t}/grad(U)")  # tensor xx xy xz yx ... : (grad U)_ij = d U_j / d x_i
    C = internal(f"{case}/{t}/C")
    owner = [int(v) for v in read_list(f"{case}/constant/polyMesh/owner")]
    neighbour = [int(v) for v in read_list(f"{case}/constant/polyMesh/neighbour")]
    faces, start = patch_faces(case, "cylinder")
    wall_cells = {owner[start + i] for i in range(len(faces))}
    nbrs = {c: [] for c in wall_cells}
    for f, nb in enumerate(neighbour):
        if owner[f] in nbrs:
            nbrs[owner[f]].append(nb)
        if nb in nbrs:
            nbrs[nb].append(owner[f])
    Fp = [0.0, 0.0]
    Fv = [0.0, 0.0]
    pw_at = []
    for i, (c, s) in enumerate(faces):
        P = owner[start + i]
        a = math.sqrt(dot(s, s))
        n = tuple(-v / a for v in s)  # into the fluid
        Q = max(nbrs[P], key=lambda q: dot(n, sub(C[q], c)))
        rP, rQ = sub(C[P], c), sub(C[Q], c)
        sP, sQ = dot(n, rP), dot(n, rQ)
        assert sP > 0 and sQ > 1.5 * sP
        tP = tuple(rP[k] - sP * n[k] for k in range(3))
        tQ = tuple(rQ[k] - sQ * n[k] for k in range(3))
        pP, pQ = p[P] - dot(gp[P], tP), p[Q] - dot(gp[Q], tQ)
        pw = (sQ * pP - sP * pQ) / (sQ - sP)
        for j in range(2):
            uP = U[P][j] - sum(gU[P][3 * k + j] * tP[k] for k in range(3))
            uQ = U[Q][j] - sum(gU[Q][3 * k + j] * tQ[k] for k in range(3))
            dudn = (uP * sQ * sQ - uQ * sP * sP) / (sP * sQ * (sQ - sP))
            Fp[j] += pw * s[j]
            Fv[j] += NU * dudn * a
        pw_at.append((math.atan2(c[1] - CY, c[0] - CX), pw))

    def wall_p(angle):
        best_lo, best_hi = None, None
        for ang, v in pw_at:
            off = math.remainder(ang - angle, 2 * math.pi)
            if off <= 0 and (best_lo is None or off > best_lo[0]):
                best_lo = (off, v)
            if off > 0 and (best_hi is None or off < best_hi[0]):
                best_hi = (off, v)
        (a0, v0), (a1, v1) = best_lo, best_hi
        return v0 + (v1 - v0) * (-a0) / (a1 - a0)

    cd = (Fp[0] + Fv[0]) / q
    cl = (Fp[1] + Fv[1]) / q
    if not verbose:
        return fo, (cd, cl), (Fp[0] / q, Fv[0] / q)
    print(f"two-cell stencil: cD {cd:.5f} (pressure {Fp[0] / q:.5f}, viscous {Fv[0] / q:.5f})"
          f"  cL {cl:.5f} (pressure {Fp[1] / q:.5f}, viscous {Fv[1] / q:.5f})")
    print(f"dp (wall-extrapolated, linear in angle) {wall_p(math.pi) - wall_p(0.0):.5f}")


def shedding(case, um, periods=3):
    ubar = 2 * um / 3
    rows = []
    for f in fo_file(case, "forceCoeffs", "coefficient.dat") or fo_file(case, "forceCoeffs",
                                                                          "forceCoeffs.dat"):
        rows += series(f)
    # v1912 coefficient.dat: Time Cd Cs Cl CmRoll CmPitch CmYaw Cd(f) ...
    rows.sort(key=lambda r: r[0])
    t = [r[0] for r in rows]
    cd = [r[1] for r in rows]
    cl = [r[3] for r in rows]
    mean = sum(cl) / len(cl)
    up = []
    for i in range(1, len(t)):
        a, b = cl[i - 1] - mean, cl[i] - mean
        if a < 0 <= b:
            up.append(t[i - 1] + (t[i] - t[i - 1]) * (-a) / (b - a))
    if len(up) < periods + 2:
        print(f"no settled shedding: {len(up)} upward crossings")
        return
    t0, t1 = up[-1 - periods], up[-1]
    period = (t1 - t0) / periods
    prev = up[-2] - up[-2 - periods]
    w = [i for i in range(len(t)) if t0 <= t[i] <= t1]
    wd = [cd[i] for i in w]
    wl = [cl[i] for i in w]

    def peak(x, sign=1):
        x = [sign * v for v in x]
        i = max(range(1, len(x) - 1), key=lambda k: x[k])
        a, b, c = x[i - 1], x[i], x[i + 1]
        den = a - 2 * b + c
        return sign * (b - (c - a) ** 2 / (8 * den) if den < 0 else b)

    print(f"onset (first upward crossing) {up[0]:.3f} s, window {t0:.4f} - {t1:.4f} s, "
          f"period drift {abs((t1 - t0) - prev) / (t1 - t0):.2e}")
    print(f"St {D / (period * ubar):.4f}  cD max {peak(wd):.4f} mean {sum(wd) / len(wd):.4f} "
          f"min {peak(wd, -1):.4f}  cL max {peak(wl):.4f} min {peak(wl, -1):.4f}")
    # Pressure / viscous split of the mean drag from the forces function object.
    frows = []
    for f in fo_file(case, "forces", "force.dat"):
        frows += series(f)
    tz = thickness(case)
    q = 0.5 * ubar * ubar * D * tz
    fw = [r for r in frows if t0 <= r[0] <= t1]
    if fw:
        mp = sum(r[4] for r in fw) / len(fw) / q
        mv = sum(r[7] for r in fw) / len(fw) / q
        print(f"mean cD split: pressure {mp:.4f}, viscous {mv:.4f}")


def instants(case, um, times):
    """Stencil minus forces-FO evaluation at written times (2D-2: offsets over a period)."""
    dd, dl = [], []
    for t in times:
        fo, st, split = steady(case, um, t, verbose=False)
        dd.append(st[0] - fo[0])
        dl.append(st[1] - fo[1])
        print(f"t {t}: cD FO {fo[0]:.4f} stencil {st[0]:.4f} (pressure {split[0]:.4f}, "
              f"viscous {split[1]:.4f}); cL FO {fo[1]:.4f} stencil {st[1]:.4f}")
    print(f"stencil minus FO over {len(times)} times: cD mean {sum(dd) / len(dd):+.4f} "
          f"(min {min(dd):+.4f}, max {max(dd):+.4f}), cL max |diff| {max(abs(v) for v in dl):.4f}")


if __name__ == "__main__":
    what, case = sys.argv[1], sys.argv[2]
    if what == "inlet":
        inlet(case, float(sys.argv[3]))
    elif what == "steady":
        steady(case, float(sys.argv[3]), sys.argv[4])
    elif what == "shedding":
        shedding(case, float(sys.argv[3]))
    elif what == "instants":
        instants(case, float(sys.argv[3]), sys.argv[4:])
    elif what == "thickness":
        print(f"{thickness(case):.17g}")
