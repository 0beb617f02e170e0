"""The strict contact law (-contact_law strict): one-sided contact at every node pair, checked on
the contact patch test and on the joint under preload, under loads that open part of it, on one
and two ranks; and its loop's cost where the active set holds."""
import h5py
import numpy as np
import pytest

from conftest import ROOT, assert_uniform_contact, make_mesh, run_boltrom, run_summary

STRICT = ["-contact_law", "strict"]
FOM = ["-fom", "-static", "false", "-modal_nev", "0"]
SCENE = ["-options_file", str(ROOT / "inputs" / "paper-step.yaml"), "-rom", "false"]


@pytest.fixture(scope="module")
def blocks(meshdir):
    return make_mesh("blocks", meshdir / "blocks.msh", 1)[0]


def assert_one_sided(fom):
    """After every converged step: no node pair penetrates by more than 1e-9 of the shortest
    contact-face edge, no closed pair is in tension beyond 1e-10 E (1e-6 of the largest
    compression here), and traction and gap are complementary."""
    chk = fom["strict_check"]
    assert chk["penetration_over_h"] <= 1e-9
    assert chk["tension_rel"] <= 1e-6
    assert chk["complementarity_rel"] <= 1e-9
    assert fom["cycles"] == 0 and fom["failures"] == 0


@pytest.mark.parametrize("penalty", ["1e4", "3e7"])
def test_strict_patch_uniform_pressure(blocks, tmp_path, penalty):
    """Two blocks pressed by p = 1 kN / 1 cm^2 with nu = 0 (uniform exact stress): every node
    pair carries p on its tributary area whatever the augmentation penalty, and no pair
    penetrates."""
    s = run_summary(["-mesh", blocks] + FOM + STRICT + [
        "-load_group", "top", "-probe_group", "top", "-load_force", "1000", "-static_contact_load",
        "-ts_dt", "1e-4", "-ts_end", "1e-4", "-material_steel_nu", "0", "-contact_penalty_factor", penalty,
        "-output", "false"], tmp_path)
    assert_uniform_contact(s["preload"], 1000.0 / 1e-4, 1e-9 * 5e-3)  # 1e-9 of the 5 mm faces


def test_strict_blocks_pulled_apart(blocks, tmp_path):
    """Pulled apart, every pair opens and carries nothing."""
    s = run_summary(["-mesh", blocks] + FOM + STRICT + [
        "-load_group", "top", "-probe_group", "top", "-load_force", "1000", "-load_direction", "0,0,1",
        "-ts_dt", "1e-5", "-ts_end", "5e-5", "-output", "false"], tmp_path)
    assert s["fom"]["active_points"] == 0
    assert s["fom"]["probe_final"] > 0


def test_strict_joint_paper_step_one_and_two_ranks(joint_small, tmp_path):
    """The preloaded joint under the paper's 10 N step: one-sided contact after every step, the
    rim of the plate overlap open under the preload, about one solve per step once the set has
    settled, the energy balance, and the same history on one and two ranks."""
    mesh, _ = joint_small
    hist = {}
    for ranks in (1, 2):
        d = tmp_path / f"r{ranks}"
        s = run_summary(SCENE + STRICT + ["-mesh", mesh, "-ts_end", "0.02", "-output_dir", str(d)], d, ranks=ranks)
        fom = s["fom"]
        assert_one_sided(fom)
        assert fom["active_points"] < fom["contact_points"]  # the preload opens the overlap's rim
        assert fom["solves"] <= 1.2 * fom["steps"]
        # the energy accounting: the work of the contact tractions at the pairs (area x mean
        # traction x gap change) closes the balance of the structure's energies to the loop's
        # tolerances (measured 8.8e-7 over 0.01 s by hand)
        assert fom["energy"]["balance_rel"] <= 1e-5
        assert fom["energy"]["external_work"] > 0
        with h5py.File(d / "paper-step.h5") as f:
            hist[ranks] = np.array(f["fom/probe"])
    # equal to the loop's gap tolerance (1e-9 of the shortest contact-face edge), which the tip's
    # lever arm over the joint magnifies: about 2e-6 of the largest value (as between penalties)
    assert np.abs(hist[1] - hist[2]).max() <= 1e-5 * np.abs(hist[1]).max()


def test_strict_result_does_not_depend_on_the_penalty(joint_small, tmp_path):
    """The penalty is only the loop's augmentation parameter: 1e6 and 3e7 E/m give the same
    history to the loop's tolerance (the first needs more solves per step)."""
    mesh, _ = joint_small
    hist, solves = {}, {}
    for pf in ("1e6", "3e7"):
        d = tmp_path / pf
        s = run_summary(SCENE + STRICT + ["-mesh", mesh, "-ts_end", "0.005", "-output_dir", str(d),
                                          "-contact_penalty_factor", pf], d)
        assert_one_sided(s["fom"])
        solves[pf] = s["fom"]["solves"]
        with h5py.File(d / "paper-step.h5") as f:
            hist[pf] = np.array(f["fom/probe"])
    assert np.abs(hist["1e6"] - hist["3e7"]).max() <= 1e-5 * np.abs(hist["3e7"]).max()
    assert solves["3e7"] < solves["1e6"]


def test_strict_extrapolated_multipliers_save_solves(joint_small, tmp_path):
    """Each step's loop starts from the multipliers extrapolated from the last two steps
    (-contact_extrapolate, the default): the same history to the loop's tolerance as starting
    from the last step's, in fewer solves where steps need more than one (a softer augmentation
    penalty, 1e7 E/m, stands in for a finer mesh here: 352 solves against 326 over 200 steps)."""
    mesh, _ = joint_small
    hist, solves = {}, {}
    for ex in ("false", "true"):
        d = tmp_path / ex
        s = run_summary(SCENE + STRICT + ["-mesh", mesh, "-ts_end", "0.02", "-output_dir", str(d),
                                          "-contact_penalty_factor", "1e7", "-contact_extrapolate", ex], d)
        assert_one_sided(s["fom"])
        solves[ex] = s["fom"]["solves"]
        with h5py.File(d / "paper-step.h5") as f:
            hist[ex] = np.array(f["fom/probe"])
    assert np.abs(hist["true"] - hist["false"]).max() <= 1e-5 * np.abs(hist["false"]).max()
    assert not np.array_equal(hist["true"], hist["false"])
    assert solves["true"] < 0.97 * solves["false"], solves


@pytest.mark.parametrize("scene", [
    ["-preload_force", "2000", "-load_force", "1000", "-load_group", "corner_point"],
    ["-preload_force", "5000", "-load_force", "300", "-load_direction", "0,1,0"],
])
def test_strict_joint_where_the_load_opens_it(joint_small, tmp_path, scene):
    """Low preloads and loads that open part of the joint: the loop converges at every step
    without any anti-cycling, in at most 5 solves per step on average, and contact stays
    one-sided."""
    mesh, _ = joint_small
    s = run_summary(SCENE + STRICT + ["-mesh", mesh, "-ts_end", "0.01", "-output_dir", str(tmp_path),
                                      "-contact_cycle_close", "false"] + scene, tmp_path)
    fom = s["fom"]
    assert_one_sided(fom)
    assert fom["solves"] <= 5 * fom["steps"]
    assert fom["active_points"] < fom["contact_points"]


def test_rom_file_of_another_law_is_refused_or_rebuilt(joint_small, tmp_path):
    """The preloaded state a ROM file holds is per contact point: a file built under the stick
    law (Gauss points) is not reused under the strict law (nodal points): refused, or rebuilt
    when -rom_rebuild names the file."""
    mesh, _ = joint_small
    rom_file = tmp_path / "joint.rom.h5"
    # one penalty for both laws, so that only the law tells the files apart
    common = SCENE + ["-mesh", mesh, "-fom", "false", "-rom", "true", "-ts_end", "0.001", "-rom_file", str(rom_file),
                      "-output", "false", "-contact_penalty_factor", "1e4"]
    first = run_summary(common + ["-contact_law", "stick"], tmp_path / "a")
    again = run_summary(common + ["-contact_law", "stick"], tmp_path / "b")
    refused = run_boltrom(common + STRICT, check=False)
    assert refused.returncode != 0 and "contact_law: the file has 'stick', the scene 'strict'" in refused.stderr
    strict = run_summary(common + STRICT + ["-rom_rebuild", str(rom_file)], tmp_path / "c")
    assert first["rom"]["source"] == "built" and again["rom"]["source"] == "file"
    assert strict["rom"]["source"] == "built"


def test_static_load_keeps_the_calibrated_preload(joint_small, tmp_path):
    """With the load in the static solve the preload is still calibrated alone: the same layer
    forces as without the load, and the pair forces differ from the preload by the load's share."""
    mesh, _ = joint_small
    s = {}
    for w in ("false", "true"):
        s[w] = run_summary(SCENE + STRICT + ["-mesh", mesh, "-ts_end", "1e-4", "-output", "false",
                                             "-static_contact_load", w], tmp_path / w)["preload"]
    assert s["true"]["layer_force_scale"] == pytest.approx(s["false"]["layer_force_scale"], rel=1e-12)
    assert s["false"]["layer_force_scale"] > 1  # the stud's layer takes part of the applied force
    for pair, f in s["true"]["normal_force_per_pair"].items():
        assert abs(-f - 20000) < 20, (pair, f)  # 10 N of load moves no pair force by more than 20 N


def test_rom_without_interface_reduction_follows_the_strict_fom(joint_small, tmp_path):
    """A ROM that closes its gaps exactly runs the strict law's own loop and band (the wide band
    is for interface-reduced ROMs only): on paper-step it follows the strict FOM closely."""
    mesh, _ = joint_small
    s = run_summary(SCENE + STRICT + ["-mesh", mesh, "-rom", "true", "-rom_n_ccm", "0", "-rom_n_jim", "0",
                                      "-ts_end", "0.01", "-output_dir", str(tmp_path), "-rom_file", str(tmp_path / "r.rom.h5")],
                    tmp_path)
    assert s["rom"]["contact_law"] == "augmented" and s["rom"]["contact_band_scale"] == 1
    assert s["errors"]["load_point"]["e_L2"] < 1e-3


def test_reclosing_pairs_stick_where_they_close(joint_small, tmp_path):
    """Under 5 kN of preload a 100 N step opens the rim and lets part of it close again within
    10 ms. By default a re-closing pair sticks where it closes (reclosed_points), on one and two
    ranks alike; -contact_reclose slide lets it slide instead. Either way contact stays one-sided."""
    mesh, _ = joint_small
    scene = SCENE + STRICT + ["-mesh", mesh, "-ts_end", "0.01", "-preload_force", "5000", "-load_force", "100"]
    hist = {}
    for ranks in (1, 2):
        d = tmp_path / f"stick{ranks}"
        s = run_summary(scene + ["-output_dir", str(d)], d, ranks=ranks)
        assert s["contact_reclose"] == "stick"
        fom = s["fom"]
        assert_one_sided(fom)
        assert fom["reclosed_points"] > 0 and fom["sliding_points"] == 0
        with h5py.File(d / "paper-step.h5") as f:
            hist[ranks] = np.array(f["fom/probe"])
    assert np.abs(hist[1] - hist[2]).max() <= 1e-5 * np.abs(hist[1]).max()
    s = run_summary(scene + ["-output", "false", "-contact_reclose", "slide"], tmp_path / "slide")
    assert_one_sided(s["fom"])
    assert s["fom"]["sliding_points"] > 0 and s["fom"]["reclosed_points"] == 0


def test_rom_where_pairs_close_again_same_on_1_and_2_ranks(joint_small, tmp_path):
    """The interface-reduced ROM on a scene where rim pairs open and close again (anchors on some
    ranks and not on others): the same bits on one and two ranks, from one ROM file (read back by
    both: a ROM as built differs from its file at round-off). Its active set changes are taken by
    low-rank updates of kept factorisations, and per solve the ROM takes only the gaps a decision
    reads (not the held points', and an open point's whole gap only near closing, where it
    becomes the anchor), testing no point where the rows prove that none would change.
    -rom_verify does it the plain way (a refactorisation at every change, every gap at every
    solve): the same decisions, and the same history up to round-off (which the near-hard
    penalty lifts to about 1e-7 of the response)."""
    mesh, _ = joint_small
    rom_file = tmp_path / "r.rom.h5"
    scene = SCENE + STRICT + ["-mesh", mesh, "-fom", "false", "-rom", "true", "-rom_file", str(rom_file),
                              "-preload_force", "5000", "-load_force", "100", "-ts_end", "0.03"]
    run_summary(scene + ["-ts_end", "1e-4", "-output", "false"], tmp_path / "build", ranks=2)
    hist, summ = {}, {}
    for name, ranks, extra in (("r2", 2, []), ("r1", 1, []), ("verify", 1, ["-rom_verify"])):
        d = tmp_path / name
        summ[name] = run_summary(scene + ["-output_dir", str(d)] + extra, d, ranks=ranks)["rom"]
        with h5py.File(d / "paper-step.h5") as f:
            hist[name] = np.array(f["rom/probe"])
    assert np.array_equal(hist["r1"], hist["r2"])
    assert summ["r1"]["held_points"] == 1 and summ["r1"]["set_updates_proved_unchanged"] > 0
    assert summ["verify"]["set_updates_proved_unchanged"] == 0
    assert summ["r1"]["low_rank_updates"] > 50 and summ["verify"]["low_rank_updates"] == 0
    assert summ["r1"]["factorizations"] < summ["verify"]["factorizations"] / 5
    assert summ["r1"]["solves"] == summ["verify"]["solves"]  # the same decisions
    assert 0 < np.abs(hist["r1"] - hist["verify"]).max() <= 1e-5 * np.abs(hist["verify"]).max()


def test_rom_opening_shapes_follow_the_fom_where_the_load_opens_the_joint(joint_small, tmp_path):
    """Under 10 kN of preload a 300 N step opens part of the plate overlap. The interface-reduced
    ROM gets opening shapes for the pairs the load changes (and the strict band with them): it
    follows the strict FOM within 0.35 % (e_L2); without them (and with the wide band) it was
    more than 1 % off. Its other points hold their preloaded state."""
    mesh, _ = joint_small
    scene = SCENE + STRICT + ["-mesh", mesh, "-rom", "true", "-ts_end", "0.03", "-preload_force", "10000", "-load_force", "300"]
    d = tmp_path / "with"
    s = run_summary(scene + ["-fom", "true", "-output_dir", str(d), "-rom_file", str(d / "r.rom.h5")], d)
    assert s["rom"]["opening_scale"] == 2 and s["rom"]["opening_krylov"] == 3 and s["rom"]["contact_band_scale"] == 1
    assert s["rom"]["held_points"] == 1 and s["rom"]["update_rank"] == (3 * s["rom"]["dim"]) // 5
    assert s["rom"]["dim"] > 200  # 151 without the shapes: the load changes some 25 node pairs
    assert s["errors"]["load_point"]["e_L2"] <= 3.5e-3
