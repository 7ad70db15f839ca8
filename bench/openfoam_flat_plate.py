# SPDX-License-Identifier: GPL-3.0-or-later
"""Helper of bench/openfoam_flat_plate.sh (pure Python 3): Cf(0.97) and the plate drag CD
(reference length 2: the mean of Cf over the plate) from simpleFoam's wallShearStress.

  openfoam_flat_plate.py cf CASE TIME
"""
import re
import sys

from openfoam_cylinder import dot, foam_list, patch_faces, strip_header

U = 1.0


def plate_shear(case, time):
    text = strip_header(open(f"{case}/{time}/wallShearStress").read())
    at = re.search(r"\bplate\s*\{", text).end()
    return foam_list(text, text.index("value", at))


def cf(case, time):
    faces, _ = patch_faces(case, "plate")
    tau = plate_shear(case, time)
    rows = sorted((c[0], abs(t[0]) / (0.5 * U * U), dot(s, s) ** 0.5) for (c, s), t in zip(faces, tau))
    area = sum(r[2] for r in rows)
    cd = sum(r[1] * r[2] for r in rows) / area
    for (x0, c0, _), (x1, c1, _) in zip(rows, rows[1:]):
        if x1 >= 0.97:
            c = c0 + (c1 - c0) * (0.97 - x0) / (x1 - x0)
            break
    print(f"{c:.6f} {cd:.6f}")


if __name__ == "__main__":
    if sys.argv[1] == "cf":
        cf(sys.argv[2], sys.argv[3])
    else:
        sys.exit(f"unknown command {sys.argv[1]}")
