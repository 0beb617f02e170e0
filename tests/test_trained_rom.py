"""The trained ROM (-rom_train): inputs at the node pairs whose contact the FOM's run changed (and
their neighbours), every closed pair the FOM did not change tied. Its reference is the FOM of the
same scene; its file serves smaller loads; a larger load makes held pairs leave their state, which the check of
every pair flags. With -rom_train static the changing pairs come from static solves instead, and no
FOM runs. Figures on more scenes and mesh levels: docs/results.md, "The trained ROM" and "The ROM
trained on static solves".

Run: /usr/bin/python3 -m pytest -q tests/test_trained_rom.py"""
import h5py
import numpy as np
import pytest

from conftest import ROOT, make_mesh, run_boltrom, run_summary

SCENE = ["-options_file", str(ROOT / "inputs" / "paper-step.yaml"), "-ts_end", "0.02", "-rom_train",
         "-krylov_order", "2", "-contact_check_every", "10"]


def test_trained_rom_follows_the_fom_where_the_default_one_drifts(joint_small, tmp_path):
    """300 N across the plates at the corner of a 2 kN joint opens part of the joint sideways:
    the default ROM is 1.3 % off there over 0.1 s (docs/results.md, "The ROM where the load opens
    the joint"); the trained one must stay within the 0.35 % asked of opening scenes."""
    mesh, _ = joint_small
    s = run_summary(SCENE + ["-mesh", mesh, "-rom_file", "", "-output", "false", "-preload_force", "2000",
                             "-load_force", "300", "-load_group", "corner_point", "-load_direction", "1,0,0",
                             "-probe_component", "0"], tmp_path)
    rom = s["rom"]
    print("e_L2", s["errors"]["load_point"]["e_L2"], "dim", rom["dim"], "inputs", rom["inputs"], rom["contact_check"])
    assert rom["n_ccm"] == 0 and rom["n_jim"] == 0 and rom["held_points"] == 1
    assert rom["inputs"] > 3 * 10  # at least ten input node pairs: the load opens the joint's side
    assert s["errors"]["load_point"]["e_L2"] <= 3.5e-3  # measured 1.6e-3


def test_trained_file_serves_smaller_loads_the_same_on_1_and_2_ranks(joint_small, tmp_path):
    """Trained at 300 N, the file runs 100 N without being rebuilt, close to that load's FOM and
    with no held pair leaving its state; read back by one and by two ranks it gives the same bits."""
    mesh, _ = joint_small
    rom_file = tmp_path / "p5k.rom.h5"
    base = SCENE + ["-mesh", mesh, "-rom_file", rom_file, "-preload_force", "5000", "-output", "false"]
    built = run_summary(base + ["-load_force", "300"], tmp_path, ranks=2, name="built")
    assert built["rom"]["source"] == "built"
    reused = run_summary(base + ["-load_force", "100"], tmp_path, ranks=2, name="reused")
    print("built", built["errors"]["load_point"]["e_L2"], "reused", reused["errors"]["load_point"]["e_L2"])
    assert reused["rom"]["source"] == "file" and reused["rom"]["dim"] == built["rom"]["dim"]
    assert reused["errors"]["load_point"]["e_L2"] <= 1e-3  # measured 1.4e-4
    assert reused["rom"]["contact_check"]["held_points_leaving"] == 0
    hist = {}
    for ranks in (1, 2):
        d = tmp_path / f"r{ranks}"
        run_summary(base + ["-load_force", "100", "-fom", "false", "-output", "true", "-output_dir", d], d, ranks=ranks)
        with h5py.File(d / "paper-step.h5") as f:
            hist[ranks] = np.array(f["rom/probe"])
    assert np.abs(hist[1]).max() > 0 and np.array_equal(hist[1], hist[2])


def test_trained_rom_pushed_beyond_its_training_is_flagged(joint_small, tmp_path):
    """Trained at 30 N and run at 300 N, the pairs the larger load opens are held: one warning
    line names the step, the summary counts them, and the response is visibly off."""
    mesh, _ = joint_small
    base = SCENE + ["-mesh", mesh, "-rom_file", tmp_path / "p5k30.rom.h5", "-preload_force", "5000", "-output", "false"]
    trained = run_summary(base + ["-load_force", "30"], tmp_path, name="trained")
    assert trained["rom"]["contact_check"]["held_points_leaving"] == 0
    proc = run_boltrom(base + ["-load_force", "300", "-summary", tmp_path / "pushed.json"])
    import json
    pushed = json.loads((tmp_path / "pushed.json").read_text())
    check = pushed["rom"]["contact_check"]
    print(check, pushed["errors"]["load_point"]["e_L2"])
    assert pushed["rom"]["source"] == "file" and check["held_points_leaving"] > 0 and check["held_first_step"] > 0
    warnings = [l for l in proc.stdout.splitlines() if "held contact points would leave their state" in l]
    assert len(warnings) == 1 and f"step {check['held_first_step']}," in warnings[0], proc.stdout
    assert pushed["errors"]["load_point"]["e_L2"] > 5e-3  # measured 2.4e-2 at 0.05 s: the flag matters


def test_tied_pairs_that_would_open_are_seen_the_same_on_1_and_2_ranks(joint_small, tmp_path):
    """A tied pair's gap cannot open, so its traction comes from the full residual at its DOFs.
    Trained at 30 N down, its tied pairs stay pressed (no tension, nothing flagged); run from the
    file at 1 kN up, the pairs the FOM opens on the far side are tied in the ROM and show tension
    (measured 3.2e8 Pa; read from their frozen gaps they showed 7 Pa), the same on 2 ranks."""
    mesh, _ = joint_small
    base = SCENE + ["-mesh", mesh, "-rom_file", tmp_path / "p5k30.rom.h5", "-preload_force", "5000", "-output", "false"]
    trained = run_summary(base + ["-load_force", "30"], tmp_path, name="trained")["rom"]["contact_check"]
    assert trained["tension_max_pa"] == 0 and trained["held_points_leaving"] == 0
    up = {r: run_summary(base + ["-load_force", "-1000", "-fom", "false"], tmp_path, ranks=r, name=f"up{r}")["rom"]["contact_check"]
          for r in (1, 2)}
    print(up)
    assert up[1]["tension_max_pa"] > 1e6 and up[1]["held_points_leaving"] > 0
    assert abs(up[2]["tension_max_pa"] - up[1]["tension_max_pa"]) <= 1e-8 * up[1]["tension_max_pa"]
    assert up[2]["held_points_leaving"] == up[1]["held_points_leaving"]


def test_trained_rom_under_friction_holds_its_sticks_and_flags_slips(joint_small, tmp_path):
    """Coulomb friction (mu 0.1, 5 kN, a sine along x): the held sticking pairs are tied in their
    normal only and keep their stick springs; trained at 30 N the ROM follows the FOM and no held
    pair leaves its cone (their tractions come from the residual); its file at 10 N does too, and
    at 300 N the pairs that would slip are flagged."""
    mesh, _ = joint_small
    base = SCENE + ["-mesh", mesh, "-rom_file", tmp_path / "mu.rom.h5", "-preload_force", "5000", "-output", "false",
                    "-krylov_order", "1", "-load_history", "sine", "-load_frequency", "50", "-load_direction", "1,0,0",
                    "-probe_component", "0", "-contact_law", "coulomb", "-contact_friction", "0.1"]
    runs = {f: run_summary(base + ["-load_force", str(f)], tmp_path, name=f"f{f}") for f in (30, 10, 300)}
    for f, r in runs.items():
        print(f, r["rom"]["source"], r["rom"]["dim"], r["errors"]["load_point"]["e_L2"], r["rom"]["contact_check"])
    assert runs[30]["rom"]["source"] == "built" and runs[10]["rom"]["source"] == "file"
    for f in (30, 10):
        assert runs[f]["errors"]["load_point"]["e_L2"] <= 1e-3  # measured 3.6e-4 and 3.2e-4
        assert runs[f]["rom"]["contact_check"]["held_points_leaving"] == 0
    assert runs[300]["rom"]["contact_check"]["held_points_leaving"] > 0
    assert runs[300]["rom"]["contact_check"]["cone_excess_max"] > 1  # a held stick far outside its cone
    assert runs[300]["errors"]["load_point"]["e_L2"] > 5e-3  # measured 1.0e-2


def test_trained_rom_refuses_a_missing_training(joint_small, tmp_path):
    mesh, _ = joint_small
    base = ["-options_file", str(ROOT / "inputs" / "paper-step.yaml"), "-mesh", mesh, "-rom_train", "-output", "false"]
    proc = run_boltrom(base + ["-rom_file", tmp_path / "none.rom.h5", "-fom", "false"], check=False)
    assert proc.returncode != 0 and "add -fom true" in proc.stderr, proc.stderr
    assert not (tmp_path / "none.rom.h5").exists()


@pytest.fixture(scope="module")
def joint_l06(meshdir):
    """Level 0.6: the paper-step's preloaded joint keeps its whole contact set (docs/results.md)."""
    return make_mesh("joint", meshdir / "joint-L0.6.msh", 0.6)[0]


def probe_of(folder):
    with h5py.File(folder / "paper-step.h5") as f:
        return {m: np.array(f[m]["probe"]).ravel() for m in ("fom", "rom") if m in f}


def test_rom_trained_on_static_solves_runs_without_the_fom_and_follows_it(joint_l06, tmp_path):
    """Paper-step at level 0.6: the paper's interface-reduced ROM (-rom_train none) drifts there,
    its rim points opening and closing while the FOM's set holds (e_L2 3.1e-2 at order 1, 1.2e-3 at
    order 2, over 0.05 s). Static solves at -/+ 2 x the load change no pair, so -rom_train static
    ties every closed pair and the ROM is the preloaded joint's linear response, built and run
    without a FOM; the default (-rom_train auto) finds the same and builds the same ROM. Their
    histories, on 1 and on 2 ranks, must follow a separate FOM run's (measured 1.0e-4, order 2);
    the paper's ROM at the same order must be five times farther (measured 1.06e-3 - 1.24e-3 in
    three runs: its 2-rank builds differ in rounding; else the test shows nothing)."""
    base = ["-options_file", ROOT / "inputs" / "paper-step.yaml", "-mesh", joint_l06, "-ts_end", "0.05",
            "-rom_file", "", "-output", "true"]
    fom_dir = tmp_path / "fom"
    run_summary(base + ["-fom", "true", "-rom", "false", "-output_dir", fom_dir], fom_dir)
    fom = probe_of(fom_dir)["fom"]
    err = {}
    for name, extra, ranks in (("static1", ["-rom_train", "static"], 1), ("auto2", [], 2),
                               ("paper", ["-rom_train", "none"], 2)):
        d = tmp_path / name
        s = run_summary(base + ["-fom", "false", "-krylov_order", "2", "-output_dir", d] + extra, d, ranks=ranks)
        rom = probe_of(d)["rom"]
        err[name] = np.linalg.norm(rom - fom) / np.linalg.norm(fom)
        assert s["rom"]["auto_tied"] == (name == "auto2")
        if name != "paper":
            assert s["rom"]["trained_on"] == "static solves" and s["rom"]["inputs"] == 2  # load and preload: no pair changes
            assert s["rom"]["contact_check"]["held_points_leaving"] == 0
            err[name + "_hist"] = rom
        else:
            assert s["rom"]["trained"] == 0 and s["rom"]["n_ccm"] > 0
    print(err)
    assert err["static1"] <= 1e-3 and err["auto2"] <= 1e-3  # measured 1.0e-4
    # builds on 1 and 2 ranks solve the preload and the static solves to the contact loop's tolerance, not bit for bit
    print("1 against 2 ranks", np.abs(err["static1_hist"] - err["auto2_hist"]).max() / np.abs(fom).max())  # measured 2.2e-7
    assert np.abs(err["static1_hist"] - err["auto2_hist"]).max() <= 1e-4 * np.abs(fom).max()
    assert err["paper"] > 5 * err["auto2"]


def test_rom_auto_file_serves_default_runs_only(joint_l06, tmp_path):
    """A ROM file the default (-rom_train auto) made tied is the tied ROM again when a later
    default run reads it (its history within 1e-7 of the build's: the build took the FOM's
    preloaded state, the reader its own), and a run asking for the paper's ROM (-rom_train none)
    refuses it, naming the difference, and leaves it as it is."""
    rom_file = tmp_path / "auto.rom.h5"
    base = ["-options_file", ROOT / "inputs" / "paper-step.yaml", "-mesh", joint_l06, "-ts_end", "0.01",
            "-rom_file", rom_file, "-output", "true", "-rom", "true"]
    built = run_summary(base + ["-fom", "true", "-output_dir", tmp_path / "a"], tmp_path / "a")
    again = run_summary(base + ["-fom", "false", "-output_dir", tmp_path / "b"], tmp_path / "b")
    assert built["rom"]["source"] == "built" and again["rom"]["source"] == "file"
    assert built["rom"]["auto_tied"] == 1 and again["rom"]["auto_tied"] == 1 and again["rom"]["trained"] == 1
    a, b = probe_of(tmp_path / "a")["rom"], probe_of(tmp_path / "b")["rom"]
    print("built against read", np.abs(a - b).max() / np.abs(a).max())
    assert np.abs(a - b).max() <= 1e-7 * np.abs(a).max()
    before = rom_file.read_bytes()
    proc = run_boltrom(base + ["-fom", "false", "-rom_train", "none", "-output_dir", tmp_path / "c"], check=False)
    assert proc.returncode != 0 and "trained: the file has 3 (auto), the scene 0 (-rom_train none)" in proc.stderr, proc.stderr
    assert rom_file.read_bytes() == before


def test_rom_auto_where_static_solves_change_points_is_the_papers_rom(joint_small, tmp_path):
    """Paper-step at level 0.5: the static solves change 8 contact points there, so the default
    (-rom_train auto) builds the paper's interface-reduced ROM, and builds it as -rom_train none
    does: with the FOM's preloaded state shared, the two ROM histories have the same bits."""
    mesh, _ = joint_small
    base = ["-options_file", ROOT / "inputs" / "paper-step.yaml", "-mesh", mesh, "-ts_end", "0.005",
            "-rom_file", "", "-output", "true", "-fom", "true", "-rom", "true"]
    hist = {}
    for name, extra in (("auto", []), ("none", ["-rom_train", "none"])):
        d = tmp_path / name
        s = run_summary(base + ["-output_dir", d] + extra, d, ranks=1)
        assert s["rom"]["auto_tied"] == 0 and s["rom"]["trained"] == 0 and s["rom"]["n_ccm"] > 0
        hist[name] = probe_of(d)["rom"]
    assert np.abs(hist["auto"]).max() > 0 and np.array_equal(hist["auto"], hist["none"])


def test_rom_train_refuses_an_unknown_source(joint_small, tmp_path):
    mesh, _ = joint_small
    proc = run_boltrom(["-options_file", ROOT / "inputs" / "paper-step.yaml", "-mesh", mesh, "-rom_train", "statics",
                        "-rom_file", tmp_path / "x.rom.h5", "-output", "false"], check=False)
    assert proc.returncode != 0 and "-rom_train statics: give auto" in proc.stderr, proc.stderr
    assert not (tmp_path / "x.rom.h5").exists()
