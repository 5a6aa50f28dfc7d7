"""Plots of the flory_rehner scene: heat maps of A_max (thesis Fig. 4.2b, 4.3b) and the PEO
T~phi curves (Fig. 4.3a). Usage: /usr/bin/python3 demos/flory_rehner/plot.py OUTPUT_DIR
Reads the CSV files and summary.json written by gelx-flory_rehner and writes PNGs beside them."""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def load_map(path):
    d = np.genfromtxt(path, delimiter=",", names=True, skip_header=1)  # past the units line
    phi = np.unique(d["phi_i"])
    eps = np.unique(d["eps_par"])
    A = d["A_max"].reshape(len(phi), len(eps))  # rows: phi_i, columns: eps (C order)
    return phi, eps, A


def heat_map(ax, path, title, bound):
    phi, eps, A = load_map(path)
    mesh = ax.pcolormesh(phi, eps, A.T, shading="auto", cmap="viridis")
    ax.axhline(0.0, color="w", ls="--", lw=1)  # prestretched above, precompressed below
    if np.nanmax(A) > bound:
        ax.contour(phi, eps, A.T, levels=[bound], colors="r", linewidths=1)
    k = np.nanargmax(A)
    i, j = np.unravel_index(k, A.shape)
    ax.plot(phi[i], eps[j], "r*", ms=10)
    ax.set_title(f"{title}\nmax {A[i, j]:.3f} at $\\phi_i$={phi[i]:.3f}, $\\epsilon$={eps[j]:.2f}",
                 fontsize=9)
    ax.set_xlabel(r"$\phi_i$")
    ax.set_ylabel(r"$\epsilon_\parallel$")
    plt.colorbar(mesh, ax=ax, label=r"$A_{max}$")


def main(out):
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
    maps = s.get("fig4_2b", [])
    if maps:
        fig, axes = plt.subplots(1, len(maps), figsize=(4.6 * len(maps), 4), squeeze=False)
        for ax, m in zip(axes[0], maps):
            heat_map(ax, os.path.join(out, m["csv"]), rf"$N\nu/V_m$ = {m['n_nu_vm']:g}",
                     m["bound_alpha0"])
        fig.suptitle(rf"Fig. 4.2b: $A_{{max}}(\phi_i, \epsilon_\parallel)$, $\alpha_0$ = "
                     rf"{maps[0]['alpha0']:g} (red: $\alpha_0^{{-3/2}}$ = {maps[0]['bound_alpha0']:.3f})")
        fig.tight_layout()
        fig.savefig(os.path.join(out, "fig4_2b_amax.png"), dpi=130)
        plt.close(fig)

    panels = []
    if os.path.exists(os.path.join(out, "amax_peo_n0.002.csv")):
        panels.append(("amax_peo_n0.002.csv", "PEO gel (Dormidontova model)"))
    if "fig4_3b_generic" in s:
        panels.append((s["fig4_3b_generic"]["csv"], r"generic gel, $\phi$-independent $\chi$"))
    if panels:
        bound = s["fig4_3b_generic"]["bound_alpha0"]
        fig, axes = plt.subplots(1, len(panels), figsize=(4.8 * len(panels), 4), squeeze=False)
        for ax, (csv, title) in zip(axes[0], panels):
            heat_map(ax, os.path.join(out, csv), title, bound)
        fig.suptitle(r"Fig. 4.3b: $A_{max}$, $N\nu/V_m$ = 0.002, $\alpha_0$ = "
                     f"{s['fig4_3b_generic']['alpha0']:g}")
        fig.tight_layout()
        fig.savefig(os.path.join(out, "fig4_3b_amax.png"), dpi=130)
        plt.close(fig)

    curves = os.path.join(out, "peo_T_phi.csv")
    if os.path.exists(curves):
        d = np.genfromtxt(curves, delimiter=",", names=True, skip_header=1)  # past the units
        fig, ax = plt.subplots(figsize=(4.8, 4))
        ax.plot(d["phi"], d["T_free"], "b.", ms=3, label="free")
        ax.plot(d["phi"], d["T_constrained"], "r.", ms=3, label="uniaxially constrained")
        ax.set_xlabel(r"$\phi$")
        ax.set_ylabel("T [K]")
        ax.set_title("Fig. 4.3a: PEO gel, T ~ $\\phi$")
        ax.legend()
        fig.tight_layout()
        fig.savefig(os.path.join(out, "fig4_3a_peo_T_phi.png"), dpi=130)
        plt.close(fig)


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: plot.py OUTPUT_DIR")
    main(sys.argv[1])
