"""The Python tools and scripts: each takes --help (exits 0, prints its usage, writes nothing), and
python/plot_history.py labels its axis with the probe the result file says it holds."""
import os
import subprocess
from pathlib import Path

import h5py
import numpy as np
import pytest
from conftest import ENV, PYTHON, ROOT

# scripts/install-deps installs system packages (apt): not a tool to run from a test
NOT_TOOLS = {"scripts/install-deps"}


def tools():
    """The executable tools of python/ and scripts/: every file with a shebang, and every module
    with a __main__ entry; modules that are only imported are left out."""
    found = []
    for folder in ("python", "scripts"):
        for path in sorted((ROOT / folder).iterdir()):
            if not path.is_file() or path.suffix not in ("", ".py"):
                continue
            text = path.read_text(errors="replace")
            name = f"{folder}/{path.name}"
            if name not in NOT_TOOLS and (text.startswith("#!") or 'if __name__ == "__main__"' in text):
                found.append(name)
    return found


TOOLS = tools()


def new_help_files(before):
    """Files in the repository's tree with 'help' in their name, not in before (a walk of the
    tree: it also holds in a copy that is not a git checkout)."""
    now = set()
    for folder, dirs, files in os.walk(ROOT):
        dirs[:] = [d for d in dirs if d != ".git"]
        now |= {os.path.relpath(os.path.join(folder, f), ROOT) for f in files if "help" in f.lower()}
    return now - (before or set())


def test_tools_found():
    """The tools named in the Makefile, the tests and the documents are among those checked."""
    for name in ("python/plot_history.py", "python/plot_static.py", "python/compare_eigen.py",
                 "python/plot_ccx_friction.py", "python/boltrom_mesh.py", "scripts/mesh-joint", "scripts/bench-offline"):
        assert name in TOOLS
    assert "python/rom_errors.py" not in TOOLS and "python/scenes.py" not in TOOLS


@pytest.mark.parametrize("tool", TOOLS)
def test_help_writes_nothing(tool, tmp_path):
    """`TOOL --help` in an empty folder: status 0, a usage text, no file there nor in the repository."""
    before = new_help_files(set())
    path = ROOT / tool
    head = path.read_text(errors="replace").splitlines()[0]
    cmd = ["bash", str(path)] if head.startswith("#!") and "bash" in head else [PYTHON, str(path)]
    proc = subprocess.run(cmd + ["--help"], cwd=tmp_path, env=ENV, capture_output=True, text=True, timeout=60)
    assert proc.returncode == 0, proc.stderr
    assert "usage" in proc.stdout.lower()
    assert list(tmp_path.iterdir()) == []
    assert new_help_files(before) == set()


def result_file(path, component=None, group=None, rom=False):
    """A tiny result file: /fom (and /rom) time and probe histories, with the probe's attributes
    where given (None: a file from before they were written)."""
    t = np.linspace(0, 1e-3, 11)
    with h5py.File(path, "w") as f:
        f["fom/time"], f["fom/probe"] = t, -1e-5 * np.sin(2e3 * t)
        if rom:
            f["rom/time"], f["rom/probe"] = t, -1.01e-5 * np.sin(2e3 * t)
        if component is not None:
            f.attrs["probe_component"] = np.int64(component)
        if group is not None:
            f.attrs["probe_group"] = group
        f.attrs["units"] = "SI: m, kg, s, N, Pa"
    return path


def test_plot_history_label(tmp_path):
    """The axis names the file's component and group; the command line writes the PNG."""
    import plot_history
    h5 = result_file(tmp_path / "tip.h5", component=0, group="tip", rom=True)
    fig = plot_history.plot([str(h5)])
    assert fig.axes[0].get_ylabel() == "displacement u_x at probe group tip [mm]"
    assert [t.get_text() for t in fig.axes[0].get_legend().get_texts()] == ["FOM (tip.h5)", "ROM (tip.h5)"]
    png = tmp_path / "out.png"
    proc = subprocess.run([PYTHON, str(ROOT / "python" / "plot_history.py"), str(png), str(h5)], cwd=tmp_path,
                          env=ENV, capture_output=True, text=True, timeout=60)
    assert proc.returncode == 0, proc.stderr
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.png", "tip.h5"]


def test_plot_history_older_and_mixed_files(tmp_path):
    """A file without the attributes gets the neutral label; files that differ in component say
    so in the legend, each its own, and the shared group stays on the axis."""
    import plot_history
    old = result_file(tmp_path / "old.h5")
    fig = plot_history.plot([str(old)])
    assert fig.axes[0].get_ylabel() == "probe displacement [mm]"
    x = result_file(tmp_path / "x.h5", component=0, group=np.bytes_(b"tip"))
    z = result_file(tmp_path / "z.h5", component=2, group="tip")
    fig = plot_history.plot([str(x), str(z)])
    assert fig.axes[0].get_ylabel() == "displacement at probe group tip [mm]"
    assert [t.get_text() for t in fig.axes[0].get_legend().get_texts()] == ["FOM (x.h5; u_x)", "FOM (z.h5; u_z)"]
    fig = plot_history.plot([str(z), str(old)])
    assert fig.axes[0].get_ylabel() == "probe displacement [mm]"
    assert [t.get_text() for t in fig.axes[0].get_legend().get_texts()] == \
        ["FOM (z.h5; u_z, group tip)", "FOM (old.h5; component not recorded, group not recorded)"]


def test_plot_history_keeps_a_result_file(tmp_path):
    """The arguments swapped (result first) is refused before the result is overwritten."""
    h5 = result_file(tmp_path / "r.h5", component=2, group="tip")
    size = h5.stat().st_size
    proc = subprocess.run([PYTHON, str(ROOT / "python" / "plot_history.py"), str(h5), str(tmp_path / "out.png")],
                          cwd=tmp_path, env=ENV, capture_output=True, text=True, timeout=60)
    assert proc.returncode == 2 and "not a result file" in proc.stderr
    assert h5.stat().st_size == size and not (tmp_path / "out.png").exists()
