#!/usr/bin/env python3
"""Like-for-like check of repro's Chapter 3 shell against CalculiX (Debian's calculix-ccx).

The same hemispherical shell (inner radius R, thickness h, clamped base) on the same mesh
(the node positions of `fem::mesh::ShellMesh::hemisphere`: n_meridian x n_thickness 8-node
elements, sizes graded from the apex), the same Gauss rule (repro's `integration: full`,
3 x 3, the default, is CalculiX's CAX8; `reduced`, 2 x 2, its CAX8R), the same St
Venant-Kirchhoff law (CalculiX's *ELASTIC with NLGEOM; repro `material:
saint_venant_kirchhoff`), the same imperfection (a point force at the inner apex pointing
away from the plate) and the same penalty slope
(1000 E/h per unit overclosure) is pressed by a rigid plate under prescribed displacement.
CalculiX: face-to-surface penalty contact against a layer of plate elements whose nodes all
carry the plate displacement (master surface from r = 1e-3 mm), over a 2-degree
segment (forces times 180 for the whole ring). repro: `fem.indent` with `stability:
tangent`.

Prints the plate force F R/(E h^3) of both at chosen delta/R, the snap (repro's located
limit point; for CalculiX the largest force before the first drop of more than 2 %), and
writes both paths (CSV) and a figure (SVG) into the output folder. Usage: `make validate-shell` or
  python3 validation/calculix/shell.py --out target/validate-shell [--repro PATH] [--apex-force A]
      [--integration reduced|full]
"""

import argparse
import math
import os
import re
import shutil
import subprocess
import sys


def graded_angles(n, grading):
    q = grading ** (1.0 / (n - 1)) if n > 1 else 1.0
    sizes = [q ** i for i in range(n)]
    total = sum(sizes)
    out, acc = [0.0], 0.0
    for s in sizes:
        acc += s
        out.append(0.5 * math.pi * acc / total)
    out[-1] = 0.5 * math.pi
    return out


def shell_mesh(R, h, nm, nt, grading):
    """Nodes {id: (r, z)}, 8-node elements [(id, [8 nodes])], and the node sets of repro's mesh."""
    phi_el = graded_angles(nm, grading)
    ni, nj = 2 * nm + 1, 2 * nt + 1
    ids, nodes = {}, {}
    for i in range(ni):
        phi = phi_el[i // 2] if i % 2 == 0 else 0.5 * (phi_el[i // 2] + phi_el[i // 2 + 1])
        for j in range(nj):
            if i % 2 == 1 and j % 2 == 1:
                continue
            rho = R + h * j / (nj - 1)
            r = 0.0 if i == 0 else rho * math.sin(phi)
            z = 0.0 if i == ni - 1 else rho * math.cos(phi)
            ids[(i, j)] = len(nodes) + 1
            nodes[ids[(i, j)]] = (r, z)
    elements = []
    for e in range(nm):
        for t in range(nt):
            i0, j0 = 2 * e, 2 * t
            at = lambda a, b: ids[(i0 + a, j0 + b)]
            conn = [at(0, 0), at(2, 0), at(2, 2), at(0, 2), at(1, 0), at(2, 1), at(1, 2), at(0, 1)]
            elements.append((len(elements) + 1, conn, t == nt - 1))
    axis = [ids[(0, j)] for j in range(nj)]
    base = [ids[(ni - 1, j)] for j in range(nj)]
    return nodes, elements, axis, base, ids[(0, 0)]


def chunks(items, n=8):
    for k in range(0, len(items), n):
        yield ", ".join(str(x) for x in items[k:k + n])


def write_deck(path, a):
    nodes, elements, axis, base, apex = shell_mesh(a.R, a.h, a.n_meridian, a.n_thickness, a.grading)
    top = a.R + a.h
    # The plate: one row of CAX4 elements above the apex, r from 1e-3 to 1.1 R.
    n_plate = 60
    first = len(nodes) + 1
    plate_nodes = {}
    for k in range(n_plate + 1):
        r = 1e-3 + (1.1 * a.R - 1e-3) * k / n_plate
        plate_nodes[first + 2 * k] = (r, top)
        plate_nodes[first + 2 * k + 1] = (r, top + 0.5 * a.h)
    plate_elements = []
    e0 = len(elements) + 1
    for k in range(n_plate):
        b = first + 2 * k
        plate_elements.append((e0 + k, [b, b + 2, b + 3, b + 1]))
    force = a.apex_force * a.E * a.h ** 3 / a.R
    k_n = 1000.0 * a.E / a.h
    lines = ["*HEADING", "repro validation: hemispherical shell pressed by a rigid plate", "*NODE, NSET=NALL"]
    lines += [f"{i}, {x[0]:.12g}, {x[1]:.12g}" for i, x in nodes.items()]
    lines += [f"{i}, {x[0]:.12g}, {x[1]:.12g}" for i, x in plate_nodes.items()]
    lines.append(f"*ELEMENT, TYPE={element_type(a)}, ELSET=ESHELL")
    lines += [f"{i}, " + ", ".join(map(str, c)) for i, c, _ in elements]
    lines.append("*ELEMENT, TYPE=CAX4, ELSET=EPLATE")
    lines += [f"{i}, " + ", ".join(map(str, c)) for i, c in plate_elements]
    lines.append("*NSET, NSET=NAXIS")
    lines += list(chunks(axis))
    lines.append("*NSET, NSET=NBASE")
    lines += list(chunks(base))
    lines.append("*NSET, NSET=NPLATE")
    lines += list(chunks(sorted(plate_nodes)))
    lines += ["*NSET, NSET=NAPEX", str(apex)]
    lines += ["*MATERIAL, NAME=SHELL", "*ELASTIC", f"{a.E}, {a.nu}", "*SOLID SECTION, ELSET=ESHELL, MATERIAL=SHELL"]
    lines += ["*MATERIAL, NAME=PLATE", "*ELASTIC", f"{1000 * a.E}, 0.3", "*SOLID SECTION, ELSET=EPLATE, MATERIAL=PLATE"]
    lines.append("*SURFACE, NAME=SSHELL")
    lines += [f"{i}, S3" for i, _, outer in elements if outer]
    lines.append("*SURFACE, NAME=SPLATE")
    lines += [f"{i}, S1" for i, _ in plate_elements]
    lines += ["*CONTACT PAIR, INTERACTION=I1, TYPE=SURFACE TO SURFACE", "SSHELL, SPLATE"]
    lines += ["*SURFACE INTERACTION, NAME=I1", "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR", f"{k_n}, 3."]
    lines += ["*BOUNDARY", "NAXIS, 1, 1", "NBASE, 1, 2"]
    lines += ["*AMPLITUDE, NAME=HOLD", "0., 1., 1., 1."]
    inc = a.delta_max / a.steps
    lines += [f"*STEP, NLGEOM, INC={50 * a.steps}", "*STATIC", f"{inc / a.delta_max}, 1., 1e-8, {inc / a.delta_max}"]
    lines += ["*CONTROLS, PARAMETERS=FIELD", "5e-4"]
    lines += ["*BOUNDARY", "NPLATE, 1, 1, 0.", f"NPLATE, 2, 2, {-a.delta_max * a.R}"]
    if force > 0:
        # CalculiX takes a point load of an axisymmetric model for the whole ring and
        # divides it over the 2-degree segment itself (its reactions are per segment).
        lines += ["*CLOAD, AMPLITUDE=HOLD", f"{apex}, 2, {-force:.10g}"]
    lines += ["*NODE PRINT, NSET=NPLATE, TOTALS=ONLY", "RF", "*END STEP", ""]
    with open(path, "w") as f:
        f.write("\n".join(lines))


def run_calculix(folder, a):
    deck = os.path.join(folder, "shell.inp")
    write_deck(deck, a)
    ccx = shutil.which("ccx") or shutil.which("ccx2.20")
    if ccx is None:
        sys.exit("validate-shell: CalculiX (ccx, Debian package calculix-ccx) is not installed")
    with open(os.path.join(folder, "ccx.log"), "w") as log:
        subprocess.run([ccx, "-i", "shell"], cwd=folder, stdout=log, stderr=subprocess.STDOUT, check=False)
    path = []
    text = open(os.path.join(folder, "shell.dat")).read() if os.path.exists(os.path.join(folder, "shell.dat")) else ""
    for m in re.finditer(r"total force \(fx,fy,fz\) for set NPLATE and time\s+(\S+)\s+(\S+)\s+(\S+)\s+(\S+)", text):
        t, fy = float(m.group(1)), float(m.group(3))
        delta = t * a.delta_max
        path.append((delta, -180.0 * fy * a.R / (a.E * a.h ** 3)))
    return path


def element_type(a):
    """CalculiX's axisymmetric 8-node element with repro's Gauss rule."""
    return {"reduced": "CAX8R", "full": "CAX8"}[a.integration]


def run_repro(folder, a, repro):
    pipeline = os.path.join(folder, "repro.yaml")
    with open(pipeline, "w") as f:
        f.write(f"""stages:
  - name: shell
    kind: fem.indent
    params:
      shell: {{R: {a.R}, h: {a.h}, E: {a.E}, nu: {a.nu}, n_meridian: {a.n_meridian}, n_thickness: {a.n_thickness},
               grading: {a.grading}, material: saint_venant_kirchhoff, integration: {a.integration}, imperfection: {{apex_force: {a.apex_force}}}}}
      delta_max: {a.delta_max}
      steps: {a.steps}
      stability: tangent
""")
    cmd = [repro, "run", pipeline, "-q", "--cache", os.path.join(folder, "cache"),
           "--figures", os.path.join(folder, "figures"), "--tables", os.path.join(folder, "tables")]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    out = subprocess.run([repro, "show", os.path.join(folder, "tables", "shell.parquet"), "--csv",
                          "--columns", "leg_id,converged,stable,state,delta_over_R,F_bar,"
                          "delta_buckling_over_R,F_buckling_bar"],
                         check=True, capture_output=True, text=True).stdout.strip().splitlines()
    path, located = [], None
    for line in out[1:]:
        leg, conv, stable, state, d, fb, d_snap, f_snap = line.split(",")
        if leg == "0" and conv == "true" and stable == "true":
            path.append((float(d), float(fb), state))
        if float(f_snap) > 0:
            located = (float(d_snap), float(f_snap))
    return path, located


def at(path, d):
    """Linear interpolation of F at delta/R = d on the rising part before the first drop."""
    for (d0, f0), (d1, f1) in zip(path, path[1:]):
        if d0 <= d <= d1 and d1 > d0:
            return f0 + (f1 - f0) * (d - d0) / (d1 - d0)
    return float("nan")


def snap(path):
    """The largest force before the first drop of more than 2 % (None: no drop)."""
    for (d0, f0), (d1, f1) in zip(path, path[1:]):
        if f1 < 0.98 * f0:
            return d0, f0
    return None


def svg(paths, file, title):
    w, hgt, m = 760, 520, 70
    xs = [p[0] for q in paths.values() for p in q]
    ys = [p[1] for q in paths.values() for p in q]
    nice = lambda v, step: step * math.ceil(v / step - 1e-9)
    x1, y1 = nice(max(xs), 0.05), nice(max(ys), 2.0)
    sx = lambda x: m + (w - 1.5 * m) * x / x1
    sy = lambda y: hgt - m - (hgt - 1.7 * m) * y / y1
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{hgt}" font-family="sans-serif" font-size="13">',
           '<rect width="100%" height="100%" fill="white"/>',
           f'<text x="{w / 2}" y="22" text-anchor="middle" font-size="15">{title}</text>',
           f'<line x1="{m}" y1="{sy(0)}" x2="{sx(x1)}" y2="{sy(0)}" stroke="black"/>',
           f'<line x1="{m}" y1="{sy(0)}" x2="{m}" y2="{sy(y1)}" stroke="black"/>']
    for k in range(6):
        x = x1 * k / 5
        out.append(f'<text x="{sx(x)}" y="{sy(0) + 18}" text-anchor="middle">{x:.3g}</text>')
        y = y1 * k / 5
        out.append(f'<text x="{m - 8}" y="{sy(y) + 4}" text-anchor="end">{y:g}</text>')
    out.append(f'<text x="{w / 2}" y="{hgt - 18}" text-anchor="middle">δ / R</text>')
    out.append(f'<text x="18" y="{hgt / 2}" text-anchor="middle" transform="rotate(-90 18 {hgt / 2})">F R / (E h³)</text>')
    colours = ["black", "#d62728", "#1f77b4"]
    for k, (name, p) in enumerate(paths.items()):
        pts = " ".join(f"{sx(x):.1f},{sy(y):.1f}" for x, y in p)
        dash = ' stroke-dasharray="6 4"' if k else ""
        out.append(f'<polyline points="{pts}" fill="none" stroke="{colours[k]}" stroke-width="1.6"{dash}/>')
        out.append(f'<line x1="{m + 20}" y1="{50 + 20 * k}" x2="{m + 50}" y2="{50 + 20 * k}" stroke="{colours[k]}"{dash}/>')
        out.append(f'<text x="{m + 58}" y="{54 + 20 * k}">{name}</text>')
    out.append("</svg>")
    open(file, "w").write("\n".join(out))


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--out", default="target/validate-shell")
    p.add_argument("--repro", default="target/debug/repro")
    p.add_argument("--R", type=float, default=15.0)
    p.add_argument("--h", type=float, default=1.0)
    p.add_argument("--E", type=float, default=1.3)
    p.add_argument("--nu", type=float, default=0.45)
    p.add_argument("--n-meridian", type=int, default=80)
    p.add_argument("--n-thickness", type=int, default=2)
    p.add_argument("--grading", type=float, default=3.0)
    p.add_argument("--apex-force", type=float, default=0.05, help="in units of F_c = E h^3 / R")
    p.add_argument("--delta-max", type=float, default=0.3, help="delta/R")
    p.add_argument("--steps", type=int, default=120)
    p.add_argument("--integration", choices=["full", "reduced"], default="full",
                   help="Gauss rule: 3 x 3 (CAX8) or 2 x 2 (CAX8R)")
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    ours, located = run_repro(a.out, a, a.repro)
    theirs = run_calculix(a.out, a)
    if not theirs:
        sys.exit(f"validate-shell: CalculiX wrote no force path (see {a.out}/ccx.log)")
    ours_flat = [(d, f) for d, f, state in ours if state == "flattened"]
    with open(os.path.join(a.out, "paths.csv"), "w") as f:
        f.write("code,delta_over_R,F_bar\n")
        f.writelines(f"repro,{d},{fb}\n" for d, fb, _ in ours)
        f.writelines(f"calculix,{d},{fb}\n" for d, fb in theirs)
    print(f"R = {a.R} mm, h = {a.h} mm, E = {a.E}, nu = {a.nu}, St Venant-Kirchhoff, apex force {a.apex_force} F_c, "
          f"{a.n_meridian} x {a.n_thickness} {element_type(a)}")
    print(f"{'delta/R':>8} {'repro':>10} {'CalculiX':>10} {'diff %':>8}")
    for d in (0.05, 0.10, 0.15):
        f1, f2 = at(ours_flat, d), at(theirs, d)
        print(f"{d:8.3f} {f1:10.4f} {f2:10.4f} {100 * (f1 - f2) / f2:8.2f}")
    # repro's snap is the limit point it locates (`F_buckling_bar`); its path may end there
    # if the jump to the inverted branch finds no state. CalculiX's is the first drop.
    s1, s2 = located or snap([(d, f) for d, f, _ in ours]), snap(theirs)
    fmt = lambda s: "no snap" if s is None else f"F_bar {s[1]:.4f} at delta/R {s[0]:.4f}"
    print(f"snap: repro {fmt(s1)}; CalculiX {fmt(s2)}")
    if s1 and s2:
        print(f"snap load difference: {100 * (s1[1] - s2[1]) / s2[1]:.2f} %")
    svg({"repro (fem.indent)": [(d, f) for d, f, _ in ours], f"CalculiX ({element_type(a)}, face-to-surface)": theirs},
        os.path.join(a.out, "validate_shell.svg"),
        f"Shell R = {a.R:g} mm, h = {a.h:g} mm, St Venant-Kirchhoff, apex force {a.apex_force:g} F_c")
    print(f"paths: {a.out}/paths.csv, figure: {a.out}/validate_shell.svg")


if __name__ == "__main__":
    main()
