"""Faults: checkpoints and restart (the continuation equals the uninterrupted run), a run
killed mid-way leaves the previous results and the last checkpoint complete, and a run with a
misspelled option or an unwritable folder stops before it computes anything, with nothing written."""
import json
import shutil
import signal
import subprocess

import h5py
import numpy as np
import pytest

from conftest import BOLTROM, ENV, ROOT, run_boltrom

SCENE = ["-options_file", ROOT / "inputs" / "paper-step.yaml", "-rom_n_ccm", "20", "-rom_n_jim", "20",
         "-ts_dt", "1e-4", "-contact_tol_lambda", "1e-9", "-contact_max_inner", "2000"]


def scene(mesh, tmp, name, end, *extra):
    return SCENE + ["-mesh", mesh, "-rom_file", tmp / "rom.h5", "-ts_end", end, "-output_dir", tmp / name,
                    "-summary", tmp / name / "summary.json"] + list(extra)


def histories(path):
    with h5py.File(path) as f:
        return {m: (f[f"/{m}/probe"][...], f[f"/{m}/energy"][...]) for m in ("fom", "rom")}


def rel(a, b):
    return np.abs(a - b).max() / np.abs(a).max()


@pytest.fixture(scope="module")
def restart_runs(joint_small, tmp_path_factory):
    """An uninterrupted 40-step run with checkpoints every 10 steps, and one without; a run
    stopped at step 20 with checkpoints every 10 steps; its continuation to step 40 on 1 rank and
    on 2 ranks (a checkpoint is keyed by the mesh as read, not by the partition)."""
    mesh, _ = joint_small
    tmp = tmp_path_factory.mktemp("restart")
    # every run reads the same ROM file: a ROM used as built differs from the same ROM read back at
    # round-off level, which the near-hard penalty lifts in the energy
    run_boltrom(scene(mesh, tmp, "build", "1e-4"))
    run_boltrom(scene(mesh, tmp, "full", "4e-3", "-checkpoint_every", "10"))
    run_boltrom(scene(mesh, tmp, "plain", "4e-3"))
    run_boltrom(scene(mesh, tmp, "part", "2e-3", "-checkpoint_every", "10"))
    base = tmp / "part" / "paper-step"
    # each continuation writes checkpoints as the uninterrupted run does, from its own copy
    for r in ("1", "2"):
        for m in ("fom", "rom"):
            shutil.copy(f"{base}-{m}.ckpt.h5", tmp / f"copy{r}-{m}.ckpt.h5")
    run_boltrom(scene(mesh, tmp, "rest1", "4e-3", "-restart", "-checkpoint_file", tmp / "copy1", "-checkpoint_every", "10"))
    run_boltrom(scene(mesh, tmp, "rest2", "4e-3", "-restart", "-checkpoint_file", tmp / "copy2", "-checkpoint_every", "10"), ranks=2)
    return mesh, tmp


def test_restart_reproduces_the_uninterrupted_run(restart_runs):
    """The continuation equals the uninterrupted run that writes the same checkpoints. The ROM's
    low-rank updates start from a new factorisation at each checkpoint (the kept ones are not in
    it), so a run without checkpoints differs from it at round-off, which the near-hard penalty
    lifts to about 1e-7 of the response; the FOM's does not."""
    _, tmp = restart_runs
    full, rest = histories(tmp / "full" / "paper-step.h5"), histories(tmp / "rest1" / "paper-step.h5")
    plain = histories(tmp / "plain" / "paper-step.h5")
    for m in ("fom", "rom"):
        assert len(full[m][0]) == len(rest[m][0]) == 41
        assert rel(full[m][0], rest[m][0]) <= 1e-12, m
        assert rel(full[m][1], rest[m][1]) <= 1e-12, m
    assert rel(plain["fom"][0], full["fom"][0]) <= 1e-12
    assert rel(plain["rom"][0], full["rom"][0]) <= 1e-5
    # the counters carry over: the restarted run reports the whole run (plus the factorisation
    # of the restored effective matrix, which a checkpoint does not hold)
    s_full = json.loads((tmp / "full" / "summary.json").read_text())
    s_rest = json.loads((tmp / "rest1" / "summary.json").read_text())
    for m in ("fom", "rom"):
        assert s_full[m]["factorizations"] <= s_rest[m]["factorizations"] <= s_full[m]["factorizations"] + 1, m
        assert s_rest[m]["solves"] == s_full[m]["solves"], m
    # and so does the FOM's energy accounting (the contact work before the checkpoint included)
    for key in ("external_work", "contact_work", "balance_rel"):
        assert s_rest["fom"]["energy"][key] == pytest.approx(s_full["fom"]["energy"][key], rel=1e-6, abs=1e-12), key


def test_restart_on_other_ranks(restart_runs):
    """A 1-rank checkpoint continued on 2 ranks: the same history to the contact loop's tolerance
    (the strict law's FOM closes gaps to 1e-9 of an edge, which the tip's lever arm lifts to about
    1e-7 of the response; the ROM's sums are exact on any partition)."""
    _, tmp = restart_runs
    full, rest = histories(tmp / "full" / "paper-step.h5"), histories(tmp / "rest2" / "paper-step.h5")
    assert rel(full["fom"][0], rest["fom"][0]) <= 1e-6
    assert rel(full["rom"][0], rest["rom"][0]) <= 1e-8


def test_restart_refuses_another_run(restart_runs, tmp_path):
    mesh, tmp = restart_runs
    base = tmp / "part" / "paper-step"
    p = run_boltrom(scene(mesh, tmp_path, "x", "4e-3", "-rom", "false", "-restart", "-checkpoint_file", base,
                          "-ts_dt", "2e-4"), check=False)
    assert p.returncode != 0 and "written by another run" in p.stderr and "dt 0.0002" in p.stderr
    assert not (tmp_path / "x" / "paper-step.h5").exists()
    p = run_boltrom(scene(mesh, tmp_path, "y", "4e-3", "-rom", "false", "-restart", "-checkpoint_file", tmp_path / "none"),
                    check=False)
    assert p.returncode != 0 and "there is no checkpoint" in p.stderr and "-checkpoint_every" in p.stderr
    p = run_boltrom(scene(mesh, tmp_path, "z", "1e-3", "-rom", "false", "-restart", "-checkpoint_file", base),
                    check=False)
    assert p.returncode != 0 and "past the end of this run" in p.stderr


def test_killed_run_leaves_previous_results(joint_small, tmp_path):
    """A first run writes results and checkpoints; a second, longer run into the same folder is
    killed mid-way: the first run's results are untouched, the last checkpoint is complete, and
    the run goes on from it."""
    mesh, _ = joint_small
    args = scene(mesh, tmp_path, "out", "1e-3", "-rom", "false", "-checkpoint_every", "5")
    run_boltrom(args)
    out = tmp_path / "out"
    before = {p.name: p.read_bytes() for p in (out / "paper-step.h5", out / "paper-step.xmf", out / "summary.json")}
    longer = scene(mesh, tmp_path, "out", "8e-3", "-rom", "false", "-checkpoint_every", "5", "-monitor")
    proc = subprocess.Popen([str(BOLTROM)] + [str(a) for a in longer], stdout=subprocess.PIPE, text=True, env=ENV, cwd=ROOT)
    for line in proc.stdout:
        if line.startswith("FOM step") and int(line.split()[2]) >= 23:
            break
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    for name, data in before.items():
        assert (out / name).read_bytes() == data, name
    with h5py.File(out / "paper-step-fom.ckpt.h5") as f:
        step = int(f["/checkpoint/history"].attrs["step"])
        # 15 counters, then per step 11 histories and the 5 pairs' forces (4 each)
        assert step >= 20 and step % 5 == 0 and len(f["/checkpoint/history"]) == 15 + (11 + 4 * 5) * (step + 1)
    p = run_boltrom(longer[:-1] + ["-restart"])
    assert f"restarted from {out / 'paper-step-fom.ckpt.h5'} at step {step}" in p.stdout
    with h5py.File(out / "paper-step.h5") as f:
        assert len(f["/fom/probe"]) == 81 and np.all(np.isfinite(f["/fom/probe"][...]))


def one_line_error(proc):
    lines = [l for l in proc.stderr.splitlines() if l.strip()]
    assert proc.returncode != 0
    assert len(lines) == 1 and lines[0].startswith("boltrom: error: "), proc.stderr
    return lines[0]


def test_misspelled_option_stops_before_any_computation(joint_small, tmp_path):
    """-ts_dtt for -ts_dt on a FOM + ROM run: the one-line error names it before the mesh is even
    read (the mesh report is a run's first line); no results, no ROM file. The same run spelled
    right (shorter) does compute, print and write all of these."""
    mesh, _ = joint_small
    good = scene(mesh, tmp_path / "good", "out", "2e-4", "-monitor")
    p = run_boltrom(good)
    assert p.stdout.startswith("Mesh ") and "Preload" in p.stdout and "FOM step" in p.stdout and "ROM step" in p.stdout
    assert (tmp_path / "good" / "rom.h5").exists() and (tmp_path / "good" / "out" / "summary.json").exists()
    bad = tmp_path / "bad"
    p = run_boltrom(scene(mesh, bad, "out", "1e-3", "-monitor", "-ts_dtt", "1e-4"), check=False)
    line = one_line_error(p)
    assert "-ts_dtt" in line and "Unknown or unused option" in line
    assert p.stdout == "" and "Preload" not in p.stdout and "step" not in p.stdout
    assert not bad.exists() or not any(bad.rglob("*")), list(bad.rglob("*"))


def test_unwritable_output_dir_stops_before_any_computation(joint_small, tmp_path):
    """An output folder under a regular file (permission bits do not stop root): the one-line error
    names the folder and -output_dir before anything is computed, and nothing is written (not the
    summary's folder, not the ROM file)."""
    mesh, _ = joint_small
    afile = tmp_path / "afile"
    afile.write_text("a file, not a folder\n")
    out = afile / "out"
    p = run_boltrom(scene(mesh, tmp_path, "x", "1e-3", "-monitor") + ["-output_dir", out, "-summary", tmp_path / "s" / "summary.json"],
                    check=False)
    line = one_line_error(p)
    assert f"Cannot create or write the directory {out}" in line and "-output_dir" in line
    assert p.stdout == ""
    assert [q.name for q in tmp_path.iterdir()] == ["afile"] and afile.read_text() == "a file, not a folder\n"
