"""The bolt's clamp force read from the stud (src/model/bolt_tension.c: the layer force less what
the squeezed element layer between the preload layers holds back), against the preload the
calibration aims at and against the contact pairs' normal forces, which the calibration uses:
two routes to the same force through different parts of the model.

Run: /usr/bin/python3 -m pytest -q tests/test_preload.py"""
import pytest

from conftest import run_summary

QUICK = ["-fom", "true", "-ts_end", "0.0005", "-static", "false", "-modal_nev", "0", "-output", "false"]


@pytest.mark.parametrize("ranks,extra,force", [(1, ["-contact_law", "strict"], 20000.0),
                                               (2, ["-contact_law", "strict"], 20000.0),
                                               (1, ["-contact_law", "coulomb", "-preload_force", "5000"], 5000.0)],
                         ids=["strict", "strict-2ranks", "coulomb-5kN"])
def test_stud_tension_is_the_calibrated_preload(joint_small, tmp_path, ranks, extra, force):
    mesh, _ = joint_small
    s = run_summary(["-mesh", mesh] + QUICK + extra, tmp_path, ranks=ranks)
    pre = s["preload"]
    # measured 5e-11 (strict, 1 and 2 ranks) and 6e-13 (coulomb) relative
    assert abs(pre["stud_tension"] - force) <= 1e-8 * force, pre
    assert abs(-pre["normal_force_per_pair"]["head_washer"] - pre["stud_tension"]) <= 1e-8 * force, pre


def test_stud_tension_without_calibration(joint_small, tmp_path):
    """Without the calibration the layers take 20 kN, of which the element layer between them
    holds back most; the stud still carries exactly what the head transmits to its washer."""
    mesh, _ = joint_small
    pre = run_summary(["-mesh", mesh, "-preload_calibrate", "false"] + QUICK, tmp_path)["preload"]
    head = -pre["normal_force_per_pair"]["head_washer"]
    assert pre["layer_force_scale"] == 1
    assert 0.05 * 20000 < pre["stud_tension"] < 0.5 * 20000, pre  # measured 3105 N
    assert abs(pre["stud_tension"] - head) <= 1e-8 * head, pre  # measured 5e-11
