#!/usr/bin/python3
"""Plots the axial load with friction against CalculiX from scripts/ccx-crosscheck JSON files
(--only friction --json FILE): the load point's u_x due to the load in both codes, with the
relative difference, and the plate interface's shear over mu times its normal force, with the
onset of macro-slip (ccx's interface at the script's --macro-slip fraction) marked.
Example: python/plot_ccx_friction.py OUT.png RUN.json [RUN.json ...]"""
import argparse
import json
from pathlib import Path

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def label(path, fr):
    return f"{Path(path).stem}: {'load point held in y, z' if fr.get('support') else 'end free'}, {fr['steps']} increments"


def main(png, *files):
    fig, (ax, ar, ap) = plt.subplots(1, 3, figsize=(15, 4.2))
    for i, path in enumerate(files):
        fr = json.loads(Path(path).read_text())["friction"]
        c = f"C{i}"
        load = [r["load"] for r in fr["curve"]]
        ax.plot(load, [r["ccx"] * 1e6 for r in fr["curve"]], "o", color=c, mfc="none", label=f"ccx, {label(path, fr)}")
        ax.plot(load, [r["boltrom"] * 1e6 for r in fr["curve"]], "-", color=c, label="boltrom")
        ar.plot(load[1:], [100 * r["rel"] for r in fr["curve"][1:]], "-o", color=c, ms=3, label=label(path, fr))
        ap.plot(load, [r["plate"]["ccx_ratio"] for r in fr["curve"]], "o", color=c, mfc="none", label=f"ccx, {label(path, fr)}")
        ap.plot(load, [r["plate"]["boltrom_ratio"] for r in fr["curve"]], "-", color=c, label="boltrom")
        if fr.get("macro_slip_load") is not None:
            for a in (ax, ar, ap):
                a.axvline(fr["macro_slip_load"], color=c, ls=":", lw=1)
    ar.axhline(2, color="k", lw=0.8, ls="--")
    ax.set_ylabel("u_x at the load point due to the load [um]")
    ar.set_ylabel("|boltrom - ccx| / ccx [%]")
    ap.set_ylabel("plate interface: shear / (mu x normal force)")
    for a in (ax, ar, ap):
        a.set_xlabel("axial load [N]")
        a.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    ar.legend(fontsize=7)
    ap.legend(fontsize=7)
    ar.set_title("dotted: macro-slip from here (ccx's plate interface at 0.98 mu N)", fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=120)
    print(f"wrote {png}")


def parse_args(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("png", metavar="OUT.png", help="the figure to write")
    parser.add_argument("files", metavar="RUN.json", nargs="+", help="JSON of scripts/ccx-crosscheck --only friction --json FILE")
    return parser.parse_args(argv)


if __name__ == "__main__":
    args = parse_args()
    main(args.png, *args.files)
