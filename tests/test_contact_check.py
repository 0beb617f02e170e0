"""The check of every node pair after the transient's steps (-contact_check_every): the full
model passes it, and a reduced model whose held pairs are made to leave their state on purpose
(its file, built at 100 N, reused at 3000 N, which opens far more of the joint) is flagged, with
one warning line and the first step in the summary.

Run: /usr/bin/python3 -m pytest -q tests/test_contact_check.py"""
from conftest import run_boltrom, run_summary

SCENE = ["-preload_force", "5000", "-ts_end", "0.01", "-static", "false", "-modal_nev", "0", "-output", "false",
         "-contact_check_every", "10"]


def test_full_model_passes_the_check(joint_small, tmp_path):
    mesh, _ = joint_small
    s = run_summary(["-mesh", mesh, "-fom", "true", "-load_force", "3000"] + SCENE, tmp_path)
    check = s["fom"]["contact_check"]
    assert check["steps_checked"] == 4  # 40 steps, every 10th
    # the strict law: no open point penetrates, no closed one pulls (smoothed through the nodes)
    assert check["penetration_max_m"] == 0 and check["tension_max_pa"] == 0, check
    assert check["held_points_leaving"] == 0 and check["held_first_step"] == -1, check


def test_held_pairs_leaving_their_state_are_flagged(joint_small, tmp_path):
    mesh, _ = joint_small
    rom = ["-mesh", mesh, "-fom", "false", "-rom", "true", "-rom_file", tmp_path / "held.rom.h5"] + SCENE
    trained = run_summary(rom + ["-load_force", "100"], tmp_path, name="trained")
    assert trained["rom"]["source"] == "built" and trained["rom"]["held_points"] == 1
    proc = run_boltrom(rom + ["-load_force", "3000", "-summary", tmp_path / "pushed.json"])
    import json
    pushed = json.loads((tmp_path / "pushed.json").read_text())
    assert pushed["rom"]["source"] == "file"
    check = pushed["rom"]["contact_check"]
    print("trained:", trained["rom"]["contact_check"], "pushed:", check)
    # measured: 928 point-steps over the 4 checks, the first at step 10, tension up to 0.8 GPa
    assert check["held_points_leaving"] > 100, check
    assert check["held_first_step"] == 10 and abs(check["held_first_time"] - 0.0025) < 1e-12, check
    assert check["tension_max_pa"] > 1e8, check
    warnings = [l for l in proc.stdout.splitlines() if "held contact points would leave their state" in l]
    assert len(warnings) == 1 and "step 10" in warnings[0], proc.stdout
    # the pushed run's held pairs leave in far greater number than the trained run's (4, measured)
    assert check["held_points_leaving"] > 10 * max(1, trained["rom"]["contact_check"]["held_points_leaving"])


def test_frictional_full_model_stays_in_the_cone(joint_small, tmp_path):
    mesh, _ = joint_small
    s = run_summary(["-mesh", mesh, "-fom", "true", "-contact_law", "coulomb", "-contact_friction", "0.1",
                     "-load_force", "300", "-ts_end", "0.005"] + SCENE[:2] + SCENE[4:], tmp_path)
    check = s["fom"]["contact_check"]
    assert check["steps_checked"] == 2
    # every closed pair's traction within mu |t_N| to round-off (measured 4.4e-16)
    assert check["cone_excess_max"] <= 1e-12 and check["tension_max_pa"] == 0, check
