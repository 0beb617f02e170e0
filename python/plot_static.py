#!/usr/bin/python3
"""Plots the deformed boundary of a boltrom result (HDF5 from -output_dir) to a PNG, coloured by
the magnitude of a vertex field.
Example: python/plot_static.py output/tied-joint/joint.h5 output/tied-joint/static.png"""
import argparse

import h5py
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

HEX_FACES = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]


def boundary_faces(cells):
    faces = np.concatenate([cells[:, f] for f in HEX_FACES])
    key = np.sort(faces, axis=1)
    _, inv, count = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    return faces[count[inv] == 1]


def main(h5path, png, field="displacement"):
    with h5py.File(h5path, "r") as f:
        x = f["/geometry/vertices"][...]
        cells = f["/topology/cells"][...].astype(int)
        u = f["/vertex_fields/" + field][...]
    faces = boundary_faces(cells)
    umax = np.abs(u).max()
    scale = 0.15 * (x.max(axis=0) - x.min(axis=0)).max() / umax if umax > 0 else 0.0
    y = (x + scale * u) * 1e3
    mag = np.linalg.norm(u, axis=1)[faces].mean(axis=1)
    fig = plt.figure(figsize=(10, 4.5))
    ax = fig.add_subplot(projection="3d")
    coll = Poly3DCollection(y[faces], array=mag * 1e3, cmap="viridis", edgecolor="k", linewidth=0.05)
    ax.add_collection3d(coll)
    for i, lab in enumerate("xyz"):
        getattr(ax, f"set_{lab}lim")(y[:, i].min(), y[:, i].max())
        getattr(ax, f"set_{lab}label")(f"{lab} [mm]")
    ax.set_box_aspect(np.ptp(y, axis=0))
    ax.view_init(elev=20, azim=-60)
    fig.colorbar(coll, ax=ax, shrink=0.6, label=f"|{field}| [mm]")
    ax.set_title(f"{field}, magnified x{scale:.0f}; max |u| = {umax * 1e3:.4f} mm")
    fig.savefig(png, dpi=130, bbox_inches="tight")
    print(f"wrote {png}")


def parse_args(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("h5path", metavar="RESULT.h5", help="a boltrom result file with a mesh and vertex fields")
    parser.add_argument("png", metavar="OUT.png", help="the figure to write")
    parser.add_argument("field", nargs="?", default="displacement", help="the vertex field to draw (default: %(default)s)")
    return parser.parse_args(argv)


if __name__ == "__main__":
    args = parse_args()
    main(args.h5path, args.png, args.field)
