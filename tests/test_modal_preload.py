"""The modes about the preloaded contact state (-modal_contact preload): K plus the contact law's
stiffness at the FOM's preloaded state, closed pairs stuck, open ones carrying nothing, slipping
or frictionless pairs no tangential stiffness.

The references are independent of the new assembly: the tied joint's own assembly (a fresh
state with every point active) where every point closes, the Courant-Fischer bound where the
preload opens points (less stiffness cannot raise any eigenvalue), and the rigid-body kinematics
of the parts that frictionless pairs leave free (each such part slides in its contact plane:
two translations and a rotation).

Run: /usr/bin/python3 -m pytest -q tests/test_modal_preload.py"""
import importlib.machinery
import importlib.util
import shutil

import h5py
import numpy as np
import pytest

from conftest import ROOT, make_mesh, run_summary

ZERO_HZ = 0.1  # a mode below this is a free motion (measured: at most 0.005 Hz)


@pytest.fixture(scope="module")
def blocks(meshdir):
    return make_mesh("blocks", meshdir / "blocks.msh", 1)[0]


@pytest.fixture(scope="module")
def joint2_small(meshdir):
    return make_mesh("joint2", meshdir / "joint2-L0.5.msh", 0.5)[0]


# the upper block pressed on the lower one by 1 kN through its top face (the lower layer is the
# clamped face): every contact point closes
BLOCK = ["-static", "false", "-output", "false", "-preload_lower_group", "clamp", "-preload_upper_group", "top",
         "-preload_force", "1000", "-preload_axis", "0,0,1", "-load_group", "top", "-probe_group", "top"]


def modes(args, tmp, name, nev=6, ranks=1):
    s = run_summary(list(args) + ["-modal_nev", nev], tmp, ranks=ranks, name=name)
    return s, s["modal"]["frequencies_hz"]


@pytest.mark.parametrize("law", ["strict", "coulomb", "stick"])
def test_every_point_closed_and_stuck_gives_the_tied_modes(blocks, tmp_path, law):
    """Under a uniform pressure every point closes and sticks: the linearised stiffness is then
    the tied joint's, which its own assembly makes from a fresh all-active state, under each
    law's penalties (strict and stick: the penalty tangentially, coulomb: the elastic stick)."""
    args = ["-mesh", blocks, "-contact_law", law] + BLOCK
    tied_s, tied = modes(args, tmp_path, f"tied-{law}")
    pre_s, pre = modes(args + ["-modal_contact", "preload"], tmp_path, f"pre-{law}")
    m = pre_s["modal"]
    assert tied_s["modal"]["contact_state"] == "tied" and m["contact_state"] == "preload"
    assert m["closed_points"] == m["stuck_points"] == m["contact_points"] == 16
    err = max(abs(a - b) / b for a, b in zip(pre, tied))
    print(f"{law}: tied {tied[0]:.3f} Hz, preloaded {pre[0]:.3f} Hz, largest difference {err:.1e}")
    assert err < 1e-8  # measured 1e-10 (the eigensolver's tolerance is 1e-10)


def test_open_points_lower_every_mode_of_the_joint(joint_small, tmp_path):
    """The level-0.5 joint (strict law, 20 kN): the preload opens some points of the plate
    interface; K_pre = K_tied less their penalties, so no mode rises (Courant-Fischer), and the
    first mode, bending about the bolt, which the open rim hardly takes part in, stays close."""
    mesh, _ = joint_small
    args = ["-mesh", mesh, "-output", "false", "-static", "false"]
    _, tied = modes(args, tmp_path, "tied")
    s, pre = modes(args + ["-modal_contact", "preload"], tmp_path, "pre")
    m = s["modal"]
    print(f"closed {m['closed_points']} of {m['contact_points']}; tied {tied}; preloaded {pre}")
    assert m["closed_points"] == m["stuck_points"] < m["contact_points"]  # measured 680 of 704
    assert s["preload"]["active_points"] == m["closed_points"]  # the FOM's preloaded state
    assert "fom" not in s  # the preload was solved for the modes alone
    for a, b in zip(pre, tied):
        assert a <= b * (1 + 1e-9), (a, b)
    assert pre[0] > 0.99 * tied[0]  # measured 92.126 against 92.171 Hz (-0.05 %)


def test_frictionless_plate_interface_lowers_the_modes_and_frees_nothing(joint_small, tmp_path):
    """Coulomb law: the plate interface without friction (-contact_plate2_plate1_friction 0)
    carries normal load only. Every mode lowers, the in-plane ones most; plate2 is still held
    in its plane by the stuck washers and the bolt, so no mode is free."""
    mesh, _ = joint_small
    args = ["-mesh", mesh, "-output", "false", "-static", "false", "-contact_law", "coulomb",
            "-modal_contact", "preload"]
    s0, stuck = modes(args, tmp_path, "mu")
    s1, free = modes(args + ["-contact_plate2_plate1_friction", "0"], tmp_path, "mu0")
    print(f"stuck {stuck}\nfrictionless plates {free}")
    assert s1["modal"]["stuck_points"] < s0["modal"]["stuck_points"]  # measured 496 and 656
    for a, b in zip(free, stuck):
        assert a < b, (a, b)
    assert free[0] > 50  # nothing free: measured 91.05 Hz (stuck 91.28 Hz)
    assert free[1] < 0.8 * stuck[1]  # measured 279.6 against 423.8 Hz (-34 %)


@pytest.mark.parametrize("clamp", ["true", "false"])
def test_all_frictionless_frees_each_part_in_its_plane(joint_small, tmp_path, clamp):
    """Coulomb law, no friction anywhere: all contact planes are z = const, so each part pressed
    only by frictionless pairs slides in x, y and turns about z. Clamped: plate2, the bolt (with
    its nut) and the two washers, 4 x 3 = 12 free motions; free-free: the 5 parts' 15 less the
    structure's 3 in-plane rigid motions, deflated: 12 again. Nothing else is free."""
    mesh, _ = joint_small
    args = ["-mesh", mesh, "-output", "false", "-static", "false", "-contact_law", "coulomb",
            "-contact_friction", "0", "-modal_contact", "preload", "-clamp", clamp]
    s, f = modes(args, tmp_path, f"free-{clamp}", nev=14)
    print(f"clamp {clamp}: {f}")
    assert s["modal"]["stuck_points"] == 0
    assert sum(x < ZERO_HZ for x in f) == 12
    assert f[12] > 50  # measured 90.3 Hz clamped, 532.9 Hz free-free


def test_blocks_without_friction_free_the_upper_block(blocks, tmp_path):
    """The pressed block on a frictionless interface: 3 free motions (x, y, about z)."""
    s, f = modes(["-mesh", blocks, "-contact_law", "coulomb", "-contact_friction", "0",
                  "-modal_contact", "preload"] + BLOCK, tmp_path, "blocks-free")
    print(f)
    assert sum(x < ZERO_HZ for x in f) == 3
    assert f[3] > 1e3  # measured 43 kHz


def test_two_bolts_with_frictionless_heads_and_nuts(joint2_small, tmp_path):
    """The two-bolt joint, both bolts preloaded (-preload_bolts 1,2): with the head and the nut
    frictionless on their washers each bolt slides and turns in its plane, 2 x 3 free motions;
    the washers stay stuck to the plates."""
    args = ["-mesh", joint2_small, "-preload_bolts", "1,2", "-output", "false", "-static", "false",
            "-contact_law", "coulomb", "-modal_contact", "preload"]
    s, f = modes(args + ["-contact_head_washer_friction", "0", "-contact_washer_nut_friction", "0"],
                 tmp_path, "two-bolts", nev=8)
    print(f)
    assert sum(x < ZERO_HZ for x in f) == 6
    assert f[6] > 50  # measured 91.9 Hz
    assert len(s["preload"]["bolts"]) == 2


def test_same_modes_on_two_ranks(joint_small, tmp_path):
    """Free-free, strict law: the preloaded state, hence the modes, do not depend on the
    partition; the rigid-body motions stay null under the preloaded stiffness."""
    mesh, _ = joint_small
    args = ["-mesh", mesh, "-output", "false", "-static", "false", "-clamp", "false", "-modal_contact", "preload"]
    _, f1 = modes(args, tmp_path, "np1", ranks=1)
    s2, f2 = modes(args, tmp_path, "np2", ranks=2)
    print(f1, f2)
    assert max(abs(a - b) / b for a, b in zip(f1, f2)) < 1e-7  # measured 3e-9
    assert s2["modal"]["rigid_modes_deflated"] == 6
    # sqrt of R' K R: round-off of the 3e7 E/m penalties (measured 0.14 Hz; the first mode 642 Hz)
    assert max(s2["modal"]["rigid_mode_frequencies_hz"]) < 1e-3 * f2[0]


def ccx_module():
    """scripts/ccx-crosscheck as a module: its mesh reader and deck writers."""
    path = ROOT / "scripts" / "ccx-crosscheck"
    loader = importlib.machinery.SourceFileLoader("ccx_crosscheck", str(path))
    spec = importlib.util.spec_from_loader("ccx_crosscheck", loader)
    mod = importlib.util.module_from_spec(spec)
    loader.exec_module(mod)
    return mod


def boltrom_open_pairs(cc, mesh, h5):
    """The node pairs (side-b tags, per pair) that boltrom's preloaded state leaves open: not
    every node at their place stuck (state 2 of fom_final_contact_state)."""
    with h5py.File(h5, "r") as f:
        x, state = f["geometry/vertices"][...], f["vertex_fields/fom_final_contact_state"][...]
    at = {}
    for xi, si in zip(np.round(x * 1e9).astype(np.int64), state):
        if si > 0:
            at.setdefault(tuple(xi), []).append(int(si))
    out = {}
    for pair in cc.PAIRS:
        _, b = mesh.pair_nodes(pair)
        keys = np.round(mesh.coords[b - 1] * 1e9).astype(np.int64)
        out[pair] = {int(t) for t, k in zip(b, keys) if not all(v == 2 for v in at[tuple(k)])}
    return out


def merged(cc, mesh, open_pairs):
    """tag -> representative tag: every node pair merged (the infinitely stiff stuck contact, as
    ccx-crosscheck's tied deck) except the open ones, given by their side-b tags."""
    parent = np.arange(len(mesh.tags) + 1)

    def find(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for pair in cc.PAIRS:
        for i, j in zip(*mesh.pair_nodes(pair)):
            if int(j) not in open_pairs.get(pair, ()):
                ri, rj = find(i), find(j)
                parent[max(ri, rj)] = min(ri, rj)
    return np.array([find(i) for i in range(len(parent))])


@pytest.mark.skipif(shutil.which("ccx") is None, reason="ccx (calculix-ccx) not installed")
def test_against_calculix_preload_then_modes(joint_small, tmp_path):
    """CalculiX on the level-0.5 joint: its own static contact solve of the same preload
    (ccx-crosscheck's contact deck: surface-to-surface penalty contact, stuck by a large friction
    coefficient, boltrom's calibrated layer forces), whose open slave nodes (no contact pressure)
    must be boltrom's open node pairs; then *FREQUENCY (C3D8I) with the closed node pairs merged,
    the infinitely stiff limit of boltrom's linearised state (strict law, 3e7 E/m), as
    ccx-crosscheck's tied deck is of the tied joint. The element difference (incompatible modes
    against C3D8I, penalty against merged nodes) shows in the tied joint as well (measured up to
    1.0 %, mode 5); what the open points change, preloaded over tied, agrees to 2e-3 (measured
    8e-4). (ccx's *FREQUENCY, PERTURBATION after its contact step is no reference yet: with the
    stick friction its first mode is 38 Hz.)"""
    mesh_path, _ = joint_small
    cc = ccx_module()
    args = ["-mesh", mesh_path, "-static", "false"]
    _, tied = modes(args + ["-output", "false"], tmp_path, "tied")
    # one step of no load: the final contact state is the preloaded one
    s, pre = modes(args + ["-fom", "true", "-load_force", "0", "-ts_dt", "1e-4", "-ts_end", "1e-4",
                           "-modal_contact", "preload", "-output_dir", tmp_path], tmp_path, "pre")
    mesh = cc.Mesh(mesh_path)
    ours = boltrom_open_pairs(cc, mesh, tmp_path / "joint.h5")
    node_force = s["preload"]["force"] * s["preload"]["layer_force_scale"] / len(np.unique(mesh.surfaces["preload_lower"]))
    slope = 1e8 * cc.MATERIALS["aluminium"][0]
    deck = cc.deck_contact(mesh, "C3D8I", 0.0, node_force, slope, 1e3, slope, 1.0)
    cc.run_ccx(tmp_path, "ccx-preload", deck[:deck.index("*END STEP") + len("*END STEP\n")], 1)  # the preload step
    pressure = cc.frd_contact(tmp_path / "ccx-preload.frd")[-1]
    theirs = {p: {int(t) for t in mesh.pair_nodes(p)[1] if pressure.get(int(t), (0.0,) * 6)[3] <= 0} for p in cc.PAIRS}
    print("open node pairs: boltrom", {p: len(v) for p, v in ours.items()}, "ccx", {p: len(v) for p, v in theirs.items()})
    assert ours == theirs and 0 < sum(map(len, ours.values())) < 30  # measured 12 of 256, the same
    ref = {}
    for name, open_pairs in (("tied", {}), ("pre", theirs)):
        deck = cc.deck_model(mesh, "C3D8I", merged(cc, mesh, open_pairs)) + "*STEP\n*FREQUENCY\n6\n*END STEP\n"
        ref[name] = cc.dat_frequencies(cc.run_ccx(tmp_path, f"ccx-{name}", deck, 1)[0])[:6]
    print(f"boltrom tied {tied}\nccx tied {ref['tied']}\nboltrom preloaded {pre}\nccx preloaded {ref['pre']}")
    for k in range(6):
        assert abs(pre[k] / ref["pre"][k] - 1) < 0.015, k  # measured 1.03 % (mode 5), tied 1.02 %
        shift_b, shift_c = pre[k] / tied[k], ref["pre"][k] / ref["tied"][k]
        assert abs(shift_b - shift_c) < 2e-3, (k, shift_b, shift_c)


def test_with_the_transient_the_modes_come_before_it(joint_small, tmp_path):
    """With -fom the modes are taken about the preload before the transient moves the state: the
    same as without the transient, and the FOM runs on after them."""
    mesh, _ = joint_small
    args = ["-mesh", mesh, "-output", "false", "-static", "false", "-modal_contact", "preload",
            "-load_force", "300", "-ts_dt", "1e-4", "-ts_end", "2e-3"]
    _, alone = modes(args, tmp_path, "alone", nev=3)
    s, with_fom = modes(args + ["-fom", "true"], tmp_path, "fom", nev=3)
    assert s["fom"]["steps"] == 20
    assert max(abs(a - b) / b for a, b in zip(with_fom, alone)) < 1e-9
