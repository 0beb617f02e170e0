"""Several bolts (-preload_bolts): the two-bolt joint (scripts/mesh-joint --kind joint2), each
bolt calibrated to its own clamp force, read from its stud; the contact pairs, which both bolts
load, carry the sum. Changing one bolt's force leaves the other's exact although its layer force
must change (the bolts load each other through the plates).

The ROM of several bolts has one preload input per bolt and starts from the FOM's calibrated
bolts; its file's fingerprint holds each bolt's force.

Run: /usr/bin/python3 -m pytest -q tests/test_bolts.py"""
import h5py
import numpy as np
import pytest

from conftest import make_mesh, run_boltrom, run_summary

QUICK = ["-fom", "true", "-ts_end", "0.0005", "-static", "false", "-modal_nev", "0", "-output", "false"]


@pytest.fixture(scope="module")
def joint2(meshdir):
    return make_mesh("joint2", meshdir / "joint2-L0.5.msh", 0.5)


def bolts(mesh, tmp, f2, ranks=1):
    s = run_summary(["-mesh", mesh, "-preload_bolts", "1,2", "-preload_2_force", f2] + QUICK, tmp, ranks=ranks)
    return s["preload"]


def test_each_bolt_clamps_with_its_own_force(joint2, tmp_path):
    mesh, info = joint2
    assert info["bolts"] == 2 and info["seam_nodes"] > 0
    first = bolts(mesh, tmp_path / "a", 10000)
    second = bolts(mesh, tmp_path / "b", 15000, ranks=2)
    for pre, f2 in ((first, 10000.0), (second, 15000.0)):
        b = pre["bolts"]
        # measured within 1e-10 relative (the calibration stops at 1e-10)
        assert abs(b["1"]["stud_tension"] - 20000) <= 1e-6 * 20000, b
        assert abs(b["2"]["stud_tension"] - f2) <= 1e-6 * f2, b
        # the pairs, shared by both bolts, carry the sum: an equilibrium the stud reading does not use
        for pair, force in pre["normal_force_per_pair"].items():
            assert abs(-force - (20000 + f2)) <= 1e-6 * (20000 + f2), (pair, force)
    # bolt 1 kept its clamp force although its layer force had to change with bolt 2's
    change = second["bolts"]["1"]["layer_force"] / first["bolts"]["1"]["layer_force"] - 1
    assert 1e-5 < abs(change) < 0.05, change  # measured +6.0e-4


def test_bolt_input_errors(joint2, tmp_path):
    mesh, _ = joint2
    for args, words in ((["-preload_bolts", "1,3"], ["preload_3_lower", "Bolt 3"]),
                        (["-preload_bolts", "1,2", "-preload_lower_group", "x"], ["drop -preload_lower_group"])):
        proc = run_boltrom(["-mesh", mesh, "-output_dir", tmp_path / "out"] + args + QUICK[:2], check=False)
        assert proc.returncode != 0, args
        line = [l for l in proc.stderr.splitlines() if "error" in l.lower()]
        assert len(line) == 1 and all(w in line[0] for w in words), (args, proc.stderr)
        assert not (tmp_path / "out").exists()


def test_restart_keeps_each_bolts_layer_force(joint2, tmp_path):
    """A checkpoint holds each bolt's calibrated layer force: the run continued from it equals the
    uninterrupted one that wrote the same checkpoints (measured bit-identical on one rank; the
    FOM's low-rank updates start from a fresh factorisation at each checkpoint)."""
    import h5py
    import numpy as np
    mesh, _ = joint2
    base = ["-mesh", mesh, "-preload_bolts", "1,2", "-preload_2_force", "10000", "-fom", "true", "-static", "false",
            "-modal_nev", "0", "-load_force", "300"]
    ckpt = ["-checkpoint_file", tmp_path / "c"]
    every = ["-checkpoint_every", "10"]
    run_boltrom(base + every + ["-ts_end", "0.005", "-checkpoint_file", tmp_path / "f", "-output_dir", tmp_path / "full"])
    run_boltrom(base + ckpt + every + ["-ts_end", "0.0025", "-output_dir", tmp_path / "a"])
    run_boltrom(base + ckpt + every + ["-ts_end", "0.005", "-restart", "-output_dir", tmp_path / "b"])
    with h5py.File(tmp_path / "full" / "joint.h5", "r") as f, h5py.File(tmp_path / "b" / "joint.h5", "r") as g:
        a, b = f["/fom/probe"][...], g["/fom/probe"][...]
    assert a.shape == b.shape == (21,)
    assert np.abs(a - b).max() <= 1e-12 * np.abs(a).max()
    other = run_boltrom(base[:3] + ["1,3"] + base[6:] + ckpt + ["-ts_end", "0.005", "-restart"], check=False)
    assert other.returncode != 0 and "preload_3_lower" in other.stderr  # bolt 3 has no layers: named first


def test_trained_rom_of_two_bolts_clamps_each_and_converges_with_the_order(joint2, tmp_path):
    """The two-bolt joint (20 and 15 kN) under a 10 N step: the trained ROM's preloaded state
    clamps each bolt to its force (its stud read in V q), and the Krylov order takes it to the FOM
    (measured e_L2 2.3e-3 at order 1, 1.3e-4 at order 2)."""
    mesh, _ = joint2
    base = ["-mesh", mesh, "-preload_bolts", "1,2", "-preload_2_force", "15000", "-fom", "true", "-rom", "true",
            "-load_force", "10", "-ts_end", "0.01", "-static", "false", "-modal_nev", "0", "-output", "false",
            "-rom_file", "", "-rom_train", "-contact_check_every", "10"]
    e = {}
    for order in (1, 2):
        s = run_summary(base + ["-krylov_order", str(order)], tmp_path, name=f"o{order}")
        e[order] = s["errors"]["load_point"]["e_L2"]
        print(order, e[order], s["rom"]["dim"], s["rom"]["bolt_stud_tension"])
        assert s["rom"]["contact_check"]["held_points_leaving"] == 0
        for bolt, target in (("1", 20000.0), ("2", 15000.0)):
            assert abs(s["rom"]["bolt_stud_tension"][bolt] - target) <= 1e-6 * target
    assert e[1] <= 5e-3 and e[2] <= 5e-4 and e[2] < e[1] / 5


def test_rom_of_two_bolts_follows_the_fom(joint2, tmp_path):
    """The ROM of the two-bolt joint (one preload input per bolt, the FOM's calibrated layer forces)
    against the FOM on a 10 N step, each bolt's clamp force read from its stud in the ROM's
    preloaded state; its file, built for bolt 2 at 15 kN, is refused at 10 kN and rebuilt into the
    same name when asked, and the rebuilt ROM's preload differs: the bolts' forces are in the
    fingerprint."""
    mesh, _ = joint2
    rom = tmp_path / "two.rom.h5"
    base = ["-mesh", mesh, "-preload_bolts", "1,2", "-fom", "true", "-rom", "true", "-load_force", "10",
            "-ts_end", "0.01", "-static", "false", "-modal_nev", "0", "-output", "false", "-rom_file", rom]

    def run(f2, name, extra=()):
        s = run_summary(base + ["-preload_2_force", f2, "-output_dir", tmp_path / name] + list(extra), tmp_path, name=name)
        with h5py.File(rom, "r") as f:
            return s, f["/rom/fingerprint"].attrs["bolt_2_force"], f["/rom/preload_unit"][...]

    a, fa, pa = run(15000, "a")
    e = a["errors"]["load_point"]["e_L2"]
    print("two bolts: e_L2", e, "dim", a["rom"]["dim"], "speedup", a["speedup"])
    assert a["rom"]["source"] == "built" and fa == 15000
    assert e < 5e-3  # measured 2.0e-3: a margin of 2.5
    # the ROM's preloaded state clamps as the FOM's: each stud read in V q (measured within 1e-10)
    for bolt, target in (("1", 20000.0), ("2", 15000.0)):
        assert abs(a["rom"]["bolt_stud_tension"][bolt] - target) <= 1e-6 * target, a["rom"]["bolt_stud_tension"]
    refused = run_boltrom(base + ["-preload_2_force", 10000], check=False)
    assert refused.returncode != 0 and "bolt_2_force: the file has 15000., the scene 10000." in refused.stderr
    b, fb, pb = run(10000, "b", ["-rom_rebuild", rom])
    assert b["rom"]["source"] == "built" and fb == 10000  # not the 15 kN file
    # another ROM: its opening shapes and preload differ (measured: dimension 174 against 168)
    assert pb.shape != pa.shape or np.abs(pb - pa).max() > 1e-3 * np.abs(pa).max()
    c, _, _ = run(10000, "c")
    assert c["rom"]["source"] == "file"
    assert c["errors"]["load_point"]["e_L2"] == pytest.approx(b["errors"]["load_point"]["e_L2"], rel=1e-6)


def test_rom_of_two_bolts_needs_the_fom(joint2, tmp_path):
    """Without the FOM's calibrated bolts (and no ROM file for them) the ROM stops with one line."""
    mesh, _ = joint2
    proc = run_boltrom(["-mesh", mesh, "-preload_bolts", "1,2", "-fom", "false", "-rom", "true", "-static", "false",
                        "-modal_nev", "0", "-output", "false", "-output_dir", tmp_path / "out"], check=False)
    assert proc.returncode != 0
    line = [l for l in proc.stderr.splitlines() if "error" in l.lower()]
    assert len(line) == 1 and "-fom true" in line[0], proc.stderr
