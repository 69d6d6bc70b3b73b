"""repro from Python, notebook style (docs/python.md): three results of the thesis in a
minute, each cell a few lines.

Run: python3 docs/examples/notebook.py [OUT_DIR]   (writes OUT_DIR/notebook.png; the cache
is $REPRO_CACHE, else ./cache, shared with `repro run`)
"""

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import repro

out = sys.argv[1] if len(sys.argv) > 1 else "."
fig, (ax1, ax2, ax3) = plt.subplots(1, 3, figsize=(15, 4.2), constrained_layout=True)

# %% 1. Sliding friction mu*(V0) of the adhesive viscoelastic cylinder (Chapter 4, BEM) at
# three Maugis parameters, with each point's error bound (the mesh's Richardson estimate).
curves = repro.sweep("bem.sweep", lambda_=[0.5, 1, 3], W=1, k=0.1, V0=np.logspace(-2, 2, 13))
for lam, c in curves.groupby("lambda"):
    ax1.errorbar(c["V0"], c["mu_star"], yerr=c["error_estimate"], marker="o", ms=3, capsize=2, label=f"λ = {lam:g}")
ax1.set(xscale="log", xlabel="V0 = v τ / a0", ylabel="μ* = μ R / a0", title="Sliding friction, W = 1, k = 0.1")
ax1.legend()
assert curves["converged"].all()
print(f"mu*(V0): {len(curves)} points, {curves.attrs['report']['counts']}")

# %% 2. The Maugis-Dugdale pull-off load against the closed forms it joins: DMT's -2 at small
# lambda, JKR's -3/2 at large (Chapter 2, Fig. 2.5).
po = repro.sweep("theory.maugis_pulloff", lambda_=np.logspace(-2, 1.5, 29))
ax2.plot(po["lambda"], po["P_bar_pulloff"], "k-", label="Maugis-Dugdale")
ax2.axhline(-2.0, ls="--", color="tab:blue", label="DMT: -2")
ax2.axhline(-1.5, ls=":", color="tab:red", label="JKR: -3/2")
ax2.set(xscale="log", xlabel="λ (Maugis)", ylabel="P̄ pull-off", title="Pull-off load (Fig. 2.5)")
ax2.legend()
assert abs(po["P_bar_pulloff"].iloc[0] + 2) < 0.05 and abs(po["P_bar_pulloff"].iloc[-1] + 1.5) < 0.05

# %% 3. One load-unload cycle of the imperfect hemispherical shell pressed by a plate
# (Chapter 3): the snap-through and the snap-back.
cycle = repro.point(
    "fem.indent",
    shell={"R": 15, "h": 1, "imperfection": {"apex_force": 0.05}},
    delta_max=0.3,
    steps=30,
    stability="tangent",
)
for leg, style in [("loading", "-"), ("unloading", "--"), ("unstable", ":")]:
    on = cycle["leg"] == leg
    ax3.plot(cycle["delta_over_R"][on], cycle["F_bar"][on], style, label=leg)
ax3.set(xlabel="δ / R", ylabel="F / F_c", title="Shell cycle, R/h = 15")
ax3.legend()
print(f"shell cycle: {len(cycle['F_bar'])} states, peak force {cycle['F_bar'].max():.3f} F_c")

fig.savefig(f"{out}/notebook.png", dpi=110)
print(f"wrote {out}/notebook.png")
