#!/usr/bin/python3
"""Plots the probe histories of boltrom HDF5 results (groups /fom, /rom) to a PNG.

The y axis names the quantity the files say they hold (root attributes probe_component and
probe_group); files written before those attributes get a neutral label. Where the files differ
in component or group, each file's legend entry says which it holds."""
import argparse
from pathlib import Path

import h5py
import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from rom_errors import errors  # noqa: E402

COMPONENTS = "xyz"


def _text(value):
    """An HDF5 string attribute (str, bytes or a one-element array of either) as str."""
    if isinstance(value, np.ndarray):
        value = value.ravel()[0] if value.size else ""
    return value.decode() if isinstance(value, bytes) else str(value)


def probe_of(attrs):
    """(component letter, group name) of a file's probe from its root attributes; None for
    either one the file does not record."""
    component = attrs.get("probe_component")
    if component is not None:
        i = int(np.asarray(component).ravel()[0])
        component = COMPONENTS[i] if 0 <= i < len(COMPONENTS) else None
    group = attrs.get("probe_group")
    if group is not None:
        group = _text(group) or None
    return component, group


def quantity(component, group):
    """The probed quantity in words: 'displacement u_z at probe group tip', shorter where the
    component or the group is unknown."""
    if component is None and group is None:
        return "probe displacement"
    text = f"displacement u_{component}" if component else "displacement"
    return text + (f" at probe group {group}" if group else " at the probe")


def labels(probes):
    """The y axis label and one legend note per file for probes, a list of (component, group):
    what all files share goes on the axis, what differs goes in the notes ('' when nothing does)."""
    components = {c for c, _ in probes}
    groups = {g for _, g in probes}
    component = next(iter(components)) if len(components) == 1 else None
    group = next(iter(groups)) if len(groups) == 1 else None
    notes = []
    for c, g in probes:
        note = []
        if len(components) > 1:
            note.append(f"u_{c}" if c else "component not recorded")
        if len(groups) > 1:
            note.append(f"group {g}" if g else "group not recorded")
        notes.append(", ".join(note))
    return quantity(component, group) + " [mm]", notes


def plot(files):
    """The figure of the probe histories in files (paths of boltrom HDF5 results)."""
    probes = []
    for path in files:
        with h5py.File(path, "r") as f:
            probes.append(probe_of(f.attrs))
    ylabel, notes = labels(probes)
    fig, ax = plt.subplots(figsize=(8, 4))
    for path, note in zip(files, notes):
        name = Path(path).name + (f"; {note}" if note else "")
        with h5py.File(path, "r") as f:
            for model in ("fom", "rom"):
                if model in f:  # lengths in m (units "SI: ..."), drawn in mm
                    ax.plot(f[model]["time"][...] * 1e3, f[model]["probe"][...] * 1e3, "-" if model == "fom" else "--",
                            label=f"{model.upper()} ({name})")
            if "fom" in f and "rom" in f:  # e_L2 and e_mean as in the summary (docs/reduction.md, "Errors and speedup")
                eL2, emean = errors(f["rom"]["probe"][...], f["fom"]["probe"][...])
                ax.set_title(f"ROM against FOM: e_L2 {eL2:.2%}, mean relative error {emean:.2%}")
    ax.set_xlabel("time [ms]")
    ax.set_ylabel(ylabel)
    ax.grid(True, alpha=0.3)
    if ax.lines:
        ax.legend()
    return fig


def main(png, *files):
    fig = plot(files)
    fig.savefig(png, dpi=130, bbox_inches="tight")
    plt.close(fig)
    print(f"wrote {png}")


def parse_args(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("png", metavar="OUT.png", help="the figure to write")
    parser.add_argument("files", metavar="RESULT.h5", nargs="+", help="boltrom result files (-output_dir)")
    args = parser.parse_args(argv)
    if Path(args.png).suffix.lower() in (".h5", ".hdf5"):  # the arguments swapped: do not overwrite a result
        parser.error(f"the first argument is the figure to write, not a result file: {args.png}")
    return args


if __name__ == "__main__":
    args = parse_args()
    main(args.png, *args.files)
