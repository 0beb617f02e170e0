#!/usr/bin/python3
"""Plots probe histories from boltrom HDF5 results (groups /fom, /rom) to a PNG.
Usage: python/plot_history.py OUT.png RESULT.h5 [RESULT.h5 ...]"""
import sys

import h5py
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from rom_errors import errors  # noqa: E402


def main(png, *files):
    fig, ax = plt.subplots(figsize=(8, 4))
    for path in files:
        with h5py.File(path, "r") as f:
            for model in ("fom", "rom"):
                if model in f:
                    ax.plot(f[model]["time"][...] * 1e3, f[model]["probe"][...] * 1e3, "-" if model == "fom" else "--",
                            label=f"{model.upper()} ({path.split('/')[-1]})")
            if "fom" in f and "rom" in f:  # e_L2 and e_mean as in the summary (docs/reduction.md, "Errors and speedup")
                eL2, emean = errors(f["rom"]["probe"][...], f["fom"]["probe"][...])
                ax.set_title(f"ROM against FOM: e_L2 {eL2:.2%}, mean relative error {emean:.2%}")
    ax.set_xlabel("time [ms]")
    ax.set_ylabel("vertical displacement at the probe [mm]")
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.savefig(png, dpi=130, bbox_inches="tight")
    print(f"wrote {png}")


if __name__ == "__main__":
    main(*sys.argv[1:])
