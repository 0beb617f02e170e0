"""boltrom against CalculiX (ccx) on the coarse joint (level 0.5), through scripts/ccx-crosscheck.

The tied joint (contact pairs merged in ccx, boltrom with a stiff penalty) must agree tightly
with full hexahedra (C3D8, the same element) at any level; the incompatible-modes elements of
the two codes are different formulations, so they agree less on this coarse mesh. The preloaded
contact comparison (ccx: stiff penalty, stick by friction) runs boltrom's strict law, which
opens the joint where ccx does (docs/verification.md, "CalculiX cross-check", has the figures at
levels 0.5 and 1).

Every figure is recomputed here from the two codes' raw values in the script's JSON and held to
a bound of its own, the measured level-0.5 value in the comment beside it. Without ccx the tests
skip, except under CI (CI=true), where a missing ccx is a failure.
"""
import json
import os
import re
import shutil
import subprocess

import pytest

from conftest import ENV, PYTHON, ROOT

# relative difference boltrom - ccx, per check of the script, and its bound here
BOUND = {
    # the same element: what is left is the stiff penalty's compliance (1e6 x E/m), largest in
    # the torsion-like third mode, as at the default penalty (3.4e-3, 2.0e-3, 2.6e-2, 1.4e-2)
    "tied full f1": 5e-6,                 # 1.65e-6
    "tied full f2": 3e-6,                 # 9.1e-7
    "tied full f3": 3e-5,                 # 1.33e-5
    "tied full u_z": 2e-5,                # 6.8e-6
    # two incompatible-mode formulations on distorted coarse elements (level 1: 1.7e-4, 4.8e-5,
    # 1.6e-3, 7.5e-4): deterministic, held with about 30 % margin
    "tied incompatible f1": 1e-3,         # 7.6e-4
    "tied incompatible f2": 3e-4,         # 2.1e-4
    "tied incompatible f3": 9.5e-3,       # 7.27e-3
    "tied incompatible u_z": 4.5e-3,      # 3.36e-3
    "contact u_z load": 5e-3,             # 3.85e-3 (level 1: 7.8e-4)
    # the 4.4 um the clamp alone moves the load point hangs on where the rim of the plate and
    # washer interfaces opens: ccx's face integration opens 12 slave nodes of 256, the strict
    # law's node pairs 24 points of 704. It is the coarse mesh's contact discretisation (level 1:
    # 6.7e-3), not noise: 1 and 2 ranks give it to 1.5e-6, so the margin is small
    "contact u_z preload": 4.5e-2,        # 4.24e-2
}
# the script's tolerances: generous, except one set below its measured figure so that the
# script's verdict is seen to fail (tied full u_z, measured 6.8e-6)
TOL = {"--tol-freq-full": 1e-4, "--tol-tied-disp-full": 1e-6,
       "--tol-freq-incompatible": 1e-2, "--tol-tied-disp-incompatible": 5e-3,
       "--tol-load-disp": 5e-3, "--tol-preload-disp": 5e-2}
PAIRS = ["head_washer", "washer_plate2", "plate2_plate1", "plate1_washer", "washer_nut"]


def rel(a, b):
    return abs(a - b) / abs(b)


def ccx_or_skip():
    """Skips a test when ccx is missing, but fails it under CI, where scripts/install-deps
    installs calculix-ccx: the cross-check must not pass there as skipped."""
    if shutil.which("ccx") is None:
        msg = "CalculiX not found: ccx is not on PATH (scripts/install-deps installs calculix-ccx)"
        if os.environ.get("CI", "").strip().lower() in ("true", "1"):
            pytest.fail(msg + "; under CI this is a failure", pytrace=False)
        pytest.skip(msg)


def run_crosscheck(mesh, work, out, args, tol, timeout):
    """scripts/ccx-crosscheck at level 0.5 on mesh with the comparison's own args and tolerances
    ({"--tol-...": value}), writing its JSON to out: the process and the JSON (which must exist,
    whatever the exit code: the tests assert on its numbers)."""
    cmd = [PYTHON, str(ROOT / "scripts" / "ccx-crosscheck"), "--level", "0.5", "--mesh", str(mesh)] + list(args)
    cmd += ["--workdir", str(work), "--json", str(out)]
    for k, v in tol.items():
        cmd += [k, str(v)]
    proc = subprocess.run(cmd, capture_output=True, text=True, env=ENV, cwd=ROOT, timeout=timeout)
    assert out.exists(), f"ccx-crosscheck wrote no JSON ({proc.returncode}):\n{proc.stdout}\n{proc.stderr}"
    return proc, json.loads(out.read_text())


@pytest.mark.parametrize("ci,outcome", [("true", "failed"), ("", "skipped")])
def test_missing_ccx_fails_under_ci(monkeypatch, ci, outcome):
    monkeypatch.setattr(shutil, "which", lambda *a, **k: None)
    monkeypatch.setenv("CI", ci)
    try:
        ccx_or_skip()
        got = "ran"
    except pytest.fail.Exception:
        got = "failed"
    except pytest.skip.Exception:
        got = "skipped"
    assert got == outcome


@pytest.fixture(scope="module")
def crosscheck(joint_small, tmp_path_factory):
    ccx_or_skip()
    mesh, _ = joint_small
    work = tmp_path_factory.mktemp("ccx")
    out = work / "crosscheck.json"
    cmd = [PYTHON, str(ROOT / "scripts" / "ccx-crosscheck"), "--level", "0.5", "--mesh", str(mesh),
           "--workdir", str(work), "--json", str(out), "--boltrom-args", "-contact_law strict"]
    for k, v in TOL.items():
        cmd += [k, str(v)]
    proc = subprocess.run(cmd, capture_output=True, text=True, env=ENV, cwd=ROOT, timeout=600)
    assert out.exists(), f"ccx-crosscheck wrote no JSON ({proc.returncode}):\n{proc.stdout}\n{proc.stderr}"
    return proc, json.loads(out.read_text())


def test_checks_printed_and_verdict(crosscheck):
    """The script prints every check with its figure, fails the one whose tolerance is below its
    measured figure, and exits 1 for it (the friction run below exits 0)."""
    proc, res = crosscheck
    printed = re.findall(r"^  (ok  |FAIL) (.+?)\s+rel (\S+) \(tol (\S+)\)$", proc.stdout, re.M)
    assert [name for _, name, *_ in printed] == list(BOUND), proc.stdout
    for (status, name, r, _), ch in zip(printed, res["checks"]):
        assert name == ch["name"] and float(r) == pytest.approx(rel(ch["boltrom"], ch["ccx"]), rel=5e-3)
    assert [name for status, name, *_ in printed if status == "FAIL"] == ["tied full u_z"]
    assert proc.returncode == 1 and "SOME CHECKS FAILED" in proc.stdout, proc.stdout + proc.stderr


def test_mesh_export(crosscheck):
    _, res = crosscheck
    assert res["min_scaled_jacobian_c3d8"] > 0.7   # every hexahedron positive in C3D8 order (0.707)


def tied_figures(res, element):
    """{check name: (ccx, boltrom with the stiff penalty)} from the tied section's raw values."""
    r = res["tied"][element]
    c, b = r["ccx"], r["boltrom_stiff"]
    out = {f"tied {element} f{k + 1}": (c["freqs"][k], b["freqs"][k]) for k in range(3)}
    out[f"tied {element} u_z"] = (c["uz"], b["uz"])
    return out


def assert_figures(res, figures):
    """Each figure within its bound, and the script's check of that name compares the same values."""
    matched = [ch["name"] for ch in res["checks"] if ch["name"] in figures]
    assert sorted(matched) == sorted(figures), matched   # each figure checked once by the script
    checks = {ch["name"]: ch for ch in res["checks"]}
    for name, (c, b) in figures.items():
        assert (checks[name]["ccx"], checks[name]["boltrom"]) == (c, b), name
        assert rel(b, c) <= BOUND[name], (name, c, b, rel(b, c))


def test_tied_full_hexahedra_agree_tightly(crosscheck):
    _, res = crosscheck
    assert_figures(res, tied_figures(res, "full"))


def test_tied_incompatible_modes(crosscheck):
    _, res = crosscheck
    assert_figures(res, tied_figures(res, "incompatible"))
    # merged nodes are the stiff limit of boltrom's penalty: its default penalty is softer
    r = res["tied"]["incompatible"]
    assert r["boltrom_default"]["freqs"][0] < r["boltrom_stiff"]["freqs"][0]


def test_preloaded_contact(crosscheck):
    _, res = crosscheck
    c, b = res["contact"]["ccx"], res["contact"]["boltrom"]
    assert_figures(res, {"contact u_z load": (c["uz_load"], b["preload_load"]["uz"] - b["preload"]["uz"]),
                         "contact u_z preload": (c["uz_preload"], b["preload"]["uz"])})
    # the same preload: boltrom's calibrated layer forces (its summary's scale), put on ccx's
    # model, clamp every pair with the 20 kN boltrom's pairs carry (ccx: 19954 N each, 2.3e-3)
    assert sorted(c["pair_normal_force_preload"]) == sorted(PAIRS)
    for pair, f in c["pair_normal_force_preload"].items():
        assert rel(f, -b["preload"]["normal_force_per_pair"][pair]) <= 4e-3, (pair, f)
    assert all(n <= 20 for n in c["iterations_per_step"]), c["iterations_per_step"]   # [13, 6]
    # closed and preloaded, the joint takes the load as the tied joint does (ccx: +0.23 %)
    assert rel(c["uz_load"], res["tied"]["incompatible"]["ccx"]["uz"]) <= 5e-3


@pytest.fixture(scope="module")
def friction(joint_small, tmp_path_factory):
    """The axial load with Coulomb friction (mu 0.1) in 8 increments to 2.4 kN, the load point
    held in y and z in both codes (the lap joint's secondary bending held, so that both solve
    the same small-rotation problem: docs/verification.md section 9)."""
    ccx_or_skip()
    mesh, _ = joint_small
    work = tmp_path_factory.mktemp("ccx-friction")
    out = work / "crosscheck.json"
    # level 0.5 measured 3.4 % at most before macro-slip; the acceptance figure, 2 %, is level 1's
    cmd = [PYTHON, str(ROOT / "scripts" / "ccx-crosscheck"), "--level", "0.5", "--mesh", str(mesh), "--ranks", "2",
           "--workdir", str(work), "--json", str(out), "--only", "friction", "--friction-support", "--tol-friction", "0.04"]
    proc = subprocess.run(cmd, capture_output=True, text=True, env=ENV, cwd=ROOT, timeout=900)
    assert out.exists(), f"ccx-crosscheck wrote no JSON ({proc.returncode}):\n{proc.stdout}\n{proc.stderr}"
    return proc, json.loads(out.read_text())["friction"], out


def test_friction_plot(friction, tmp_path):
    """python/plot_ccx_friction.py draws the run's JSON (the figure of docs/verification.md)."""
    *_, out = friction
    png = tmp_path / "friction.png"
    subprocess.run([PYTHON, str(ROOT / "python" / "plot_ccx_friction.py"), str(png), str(out)], check=True,
                   capture_output=True, text=True, cwd=ROOT, timeout=120)
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 20000


def test_friction_curve_before_macro_slip(friction):
    """u_x due to the load within 4 % of ccx's at every increment before ccx's plate interface
    slides as a whole, which both codes reach at the same increment (2.1 kN: the shear at 0.98 of
    mu times the normal force), near mu times the 20 kN clamp."""
    proc, fr, _ = friction
    assert proc.returncode == 0 and "all within tolerance" in proc.stdout, proc.stdout + proc.stderr
    assert fr["support"] and fr["macro_slip_load"] == pytest.approx(2100.0)
    onset = [r for r in fr["curve"] if r["load"] == fr["macro_slip_load"]][0]
    assert onset["plate"]["boltrom_ratio"] >= 0.98
    before = [r for r in fr["curve"][1:] if r["load"] < fr["macro_slip_load"]]
    assert len(before) == 6 and max(rel(r["boltrom"], r["ccx"]) for r in before) <= 0.04
    assert all(r["plate"]["boltrom_ratio"] < 0.98 for r in before)


def test_friction_interface_forces_agree(friction):
    """The force the plate interface transmits: the two codes within 2 % of each other at every
    increment before macro-slip (measured 1.4 %), the clamp within 1.5 % (1.3 %; ccx's drops by
    1 % at the load's first increment)."""
    _, fr, _ = friction
    before = [r for r in fr["curve"][1:] if r["load"] < fr["macro_slip_load"]]
    assert len(before) == 6
    for r in before:
        p = r["plate"]
        assert p["boltrom_shear"] == pytest.approx(p["ccx_shear"], rel=0.02), r["load"]
        assert p["boltrom_normal"] == pytest.approx(p["ccx_normal"], rel=0.015), r["load"]
