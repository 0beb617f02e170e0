"""The Brake-Reuss beam (scripts/mesh-joint --kind brb): its mesh against the geometry it
describes, its three bolts each clamped with its own force, free-free, and its tied modes against
an independent eigensolver.

Run: /usr/bin/python3 -m pytest -q tests/test_brb.py"""
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from conftest import load_petsc_matrix, make_mesh, run_summary

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "python"))
import boltrom_mesh as bm  # noqa: E402
from mesh_brb import BRB  # noqa: E402

STAINLESS = ["-materials", "stainless", "-material_stainless_E", "192e9", "-material_stainless_nu", "0.29",
             "-material_stainless_rho", "7800", "-part_material",
             ",".join("%s:stainless" % p for p in ("beam1", "beam2", "bolt", "washer_head", "washer_nut", "nut"))]
FREE = ["-clamp", "false", "-output", "false"] + STAINLESS
PRELOAD = ["-preload_bolts", "1,2,3", "-preload_force", "12000", "-load_force", "0", "-fom", "true",
           "-ts_end", "0.0005", "-static", "false", "-modal_nev", "0"]


@pytest.fixture(scope="module")
def brb(meshdir):
    return make_mesh("brb", meshdir / "brb-L0.5.msh", 0.5)


def test_brb_mesh_is_the_beam_it_describes(brb):
    """Each half-beam's volume against the closed form (full section, the 12.7 mm lap, three
    holes as the inscribed polygons the O-grid makes), node-matched pairs over all three bolts,
    and check-mesh's verdict."""
    mesh, info = brb
    G, n = BRB, info["divisions"]["n_theta"]
    hole = 0.5 * n * G["r_hole"] ** 2 * math.sin(2 * math.pi / n)
    beam = 0.300 * G["width"] * 2 * G["t"] + 0.120 * G["width"] * G["t"] - 3 * hole * G["t"]
    for part in ("beam1", "beam2"):
        assert abs(info["volume_per_part"][part] - beam) <= 1e-12 * beam, (part, info["volume_per_part"][part], beam)
    faces = info["faces_per_surface"]
    for pair in ("head_washer", "washer_beam2", "beam2_beam1", "beam1_washer", "washer_nut"):
        assert faces["contact_%s_a" % pair] == faces["contact_%s_b" % pair] > 0, pair
    # the lap: 120 x 25.4 mm less three holes, in faces of both sides
    for b in (1, 2, 3):
        assert faces["preload_%d_lower" % b] == faces["preload_%d_upper" % b] > 0
    assert min(info["min_scaled_jacobian_per_part"].values()) > 0.7
    proc = subprocess.run([sys.executable, str(ROOT / "scripts" / "check-mesh"), str(mesh)],
                          capture_output=True, text=True)
    assert proc.returncode == 0 and "no problems found" in proc.stdout, proc.stdout
    assert "-preload_bolts 1,2,3" in proc.stdout


def test_brb_mesh_size_grows_with_level():
    """A fine level reaches the issue's 200k DOFs (level 1.6: counted, not written)."""
    rep = bm.report(bm.build("brb", 1.6))
    assert rep["dofs"] > 200000, rep["dofs"]


def test_each_brb_bolt_clamps_with_its_own_force(brb, tmp_path):
    """Three bolts, free-free: each stud carries its own preload (1e-6; measured 2e-13), the lap and
    the washers carry their sum; bolt 2 changed (that run on 2 ranks) leaves bolts 1 and 3 exact."""
    mesh, _ = brb
    a = run_summary(["-mesh", mesh] + FREE + PRELOAD, tmp_path / "a")["preload"]
    b = run_summary(["-mesh", mesh, "-preload_2_force", "6000"] + FREE + PRELOAD, tmp_path / "b", ranks=2)["preload"]
    for pre, forces in ((a, (12000, 12000, 12000)), (b, (12000, 6000, 12000))):
        for name, f in zip("123", forces):
            assert abs(pre["bolts"][name]["stud_tension"] - f) <= 1e-6 * f, (name, pre["bolts"])
        for pair, force in pre["normal_force_per_pair"].items():
            assert abs(-force - sum(forces)) <= 1e-6 * sum(forces), (pair, force)
        assert pre["penetration_max"] < 1e-9 * BRB["t"]
    # bolt 2's change moved its neighbours' layer forces (they share the beams), yet both stay exact
    change = b["bolts"]["1"]["layer_force"] / a["bolts"]["1"]["layer_force"] - 1
    assert 1e-6 < abs(change) < 0.1, change


def test_free_brb_tied_modes_against_an_independent_eigensolver(brb, tmp_path):
    """The free tied beam: boltrom's elastic frequencies (SLEPc, rigid motions deflated) against
    scipy's ARPACK on the exported matrices (rigid modes left in), to 1e-6; the six rigid
    frequencies under K below 1e-3 of the first elastic one; the first two modes are the two
    bending planes (z lower: the lap's steps weaken it, y nearly a whole beam)."""
    import scipy.sparse.linalg as sla

    mesh, _ = brb
    exp = tmp_path / "matrices"
    s = run_summary(["-mesh", mesh, "-static", "false", "-modal_nev", "4", "-contact_law", "stick",
                     "-contact_penalty_factor", "200", "-export_matrices", exp] + FREE, tmp_path)

    K, M = load_petsc_matrix(exp / "K_tied.petsc"), load_petsc_matrix(exp / "M.petsc")
    w, V = sla.eigsh(K, k=10, M=M, sigma=-(2 * np.pi * 100) ** 2, which="LM")
    order = np.argsort(w)
    w, V = w[order], V[:, order]
    ref = np.sqrt(w[6:]) / (2 * np.pi)
    f = np.array(s["modal"]["frequencies_hz"])
    print("free BRB:", f, "scipy:", ref, "rigid:", s["modal"]["rigid_mode_frequencies_hz"])
    assert np.abs(w[:6]).max() < 1e-6 * w[6]
    assert np.abs(f - ref).max() <= 1e-6 * ref[0], (f, ref)
    assert max(s["modal"]["rigid_mode_frequencies_hz"]) < 1e-3 * f[0]
    # DOFs are 3 per vertex: component c of mode k is V[c::3, k]
    share = [[np.sum(V[c::3, 6 + k] ** 2) / np.sum(V[:, 6 + k] ** 2) for c in range(3)] for k in range(2)]
    assert share[0][2] > 0.95 and share[1][1] > 0.95, share


def test_backbone_reader_recovers_a_known_decay(tmp_path):
    """scripts/brb-backbone's reader (matrix pencil per window) on a synthetic ring-down: a rigid
    drift, a first mode whose damping ratio grows with its amplitude like a joint's, and a third
    mode; it returns the first mode's frequency to 1e-4 and damping ratio to 2 % of itself."""
    import importlib.machinery
    import importlib.util
    import h5py
    loader = importlib.machinery.SourceFileLoader("brb_backbone", str(ROOT / "scripts" / "brb-backbone"))
    spec = importlib.util.spec_from_loader("brb_backbone", loader)
    bb = importlib.util.module_from_spec(spec)
    loader.exec_module(bb)
    dt, f1, z1, f3 = 1e-4, 168.0, 0.01, 1140.0
    t = np.arange(0, 0.12, dt)
    w1 = 2 * np.pi * f1
    u = (0.03 + 0.2 * t + 5e-5 * np.exp(-z1 * w1 * t) * np.cos(w1 * np.sqrt(1 - z1 ** 2) * t)
         + 1e-6 * np.cos(2 * np.pi * f3 * t + 0.3))
    with h5py.File(tmp_path / "r.h5", "w") as f:
        f["fom/time"], f["fom/probe"] = t, u
    rows = bb.modal_backbone(tmp_path / "r.h5", 0.0, 1.0, 170.0)
    assert len(rows) >= 10
    for r in rows:
        assert abs(r["freq"] / (f1 * np.sqrt(1 - z1 ** 2)) - 1) < 1e-4, r
        assert abs(r["zeta"] / z1 - 1) < 0.02, r
        assert abs(r["probe_amp"] / (5e-5 * np.exp(-z1 * w1 * r["t"])) - 1) < 0.02, r


def test_backbones_are_compared_at_equal_amplitude():
    """scripts/brb-backbone's comparison of a ROM's backbone with the FOM's: a ROM on the FOM's
    very curve (damping ratio proportional to amplitude, frequency falling with it) whose
    ring-down decays a little faster is within the tolerances at equal amplitude, though its
    periods, one by one, meet the FOM's at other amplitudes (10 % apart in damping ratio); a ROM
    with 8 % more damping at every amplitude is not within, and its 8 % is what is reported."""
    import importlib.machinery
    import importlib.util
    loader = importlib.machinery.SourceFileLoader("brb_backbone", str(ROOT / "scripts" / "brb-backbone"))
    spec = importlib.util.spec_from_loader("brb_backbone", loader)
    bb = importlib.util.module_from_spec(spec)
    loader.exec_module(bb)

    def curve(amps, zscale=1.0):
        return [dict(modal_amp=a, freq=168.0 - 2e4 * a, zeta=zscale * 100 * a) for a in amps]

    fom = curve(1e-4 * 0.95 ** np.arange(14))
    late = curve(0.9e-4 * 0.95 ** np.arange(14))   # the same curve, every period at 0.9 x the amplitude
    df, dz, ok, n = bb.at_equal_amplitude(fom, late)
    assert ok and n == 11 and df < 1e-5 and dz < 1e-3, (df, dz, n)  # the FOM periods within the ROM's range
    pf, pz, pok = bb.rom_agrees(fom, late)
    assert not pok and abs(pz - 0.1) < 1e-9, (pf, pz)
    more = curve(1e-4 * 0.95 ** np.arange(14), zscale=1.08)
    df, dz, ok, n = bb.at_equal_amplitude(fom, more)
    assert not ok and abs(dz - 0.08) < 1e-9 and n == 14, (dz, n)
