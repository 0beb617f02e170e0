"""Faults: checkpoints and restart (the continuation equals the uninterrupted run, on the same or
another number of ranks), a run killed while it writes a checkpoint or a ROM file leaves the
previous results, checkpoint and ROM file as they were, and a run with a misspelled option or an
unwritable folder stops before it computes anything, with nothing written."""
import json
import shutil
import signal
import subprocess
import time
from pathlib import Path

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
    on 2 ranks (a checkpoint is keyed by the mesh as read, not by the partition); the same stop
    made on 2 ranks, continued on 1."""
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
    # and the other way: stopped at step 20 on 2 ranks, continued on 1
    run_boltrom(scene(mesh, tmp, "part2", "2e-3", "-checkpoint_every", "10"), ranks=2)
    run_boltrom(scene(mesh, tmp, "rest21", "4e-3", "-restart", "-checkpoint_file", tmp / "part2" / "paper-step",
                      "-checkpoint_every", "10"))
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
    """A 1-rank checkpoint continued on 2 ranks, and a 2-rank one continued on 1, against the
    uninterrupted 1-rank run. The FOM's factorisation and sums depend on the partition at
    round-off, which the strict law's contact loop (gaps closed to 1e-9 of an edge) and the tip's
    lever arm lift: measured 2.3e-7 (1 -> 2) and 1.0e-7 (2 -> 1) of the probe's history, 1.4e-9 and
    2.8e-10 of the energy's; the bounds leave a factor 4 or more. The ROM's sums are exact on any
    partition: its histories came out bit-identical both ways."""
    _, tmp = restart_runs
    full = histories(tmp / "full" / "paper-step.h5")
    for name in ("rest2", "rest21"):
        rest = histories(tmp / name / "paper-step.h5")
        assert len(rest["fom"][0]) == len(rest["rom"][0]) == 41, name
        assert rel(full["fom"][0], rest["fom"][0]) <= 1e-6, name
        assert rel(full["fom"][1], rest["fom"][1]) <= 1e-8, name
        assert rel(full["rom"][0], rest["rom"][0]) <= 1e-12, name
        assert rel(full["rom"][1], rest["rom"][1]) <= 1e-12, name


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


def kill_while_written(args, final, accept=lambda: True, attempts=3):
    """Starts boltrom on args and SIGKILLs it while it writes final under its temporary name
    (final + ".tmp"), once accept() holds. The process is stopped (SIGSTOP) as soon as the
    temporary file is seen; if it is still there, the rename has not happened: final is copied as
    it is then and the process killed. Returns final's bytes at the kill."""
    tmp = Path(str(final) + ".tmp")
    for _ in range(attempts):
        proc = subprocess.Popen([str(BOLTROM)] + [str(a) for a in args], stdout=subprocess.DEVNULL,
                                stderr=subprocess.DEVNULL, env=ENV, cwd=ROOT)
        while proc.poll() is None:
            if tmp.exists():
                proc.send_signal(signal.SIGSTOP)
                if tmp.exists() and final.exists() and accept():
                    data = final.read_bytes()
                    proc.send_signal(signal.SIGKILL)
                    proc.wait()
                    assert tmp.exists()  # killed before the rename: the write was under way
                    return data
                proc.send_signal(signal.SIGCONT)
                while tmp.exists() and proc.poll() is None:  # this write is let through
                    time.sleep(1e-4)
            time.sleep(1e-4)
    raise AssertionError(f"{final}: no write caught in {attempts} runs")


def test_killed_run_leaves_previous_results(joint_small, tmp_path):
    """A first run writes results and checkpoints; a second, longer run into the same folder is
    killed while it writes a checkpoint after step 20: the first run's results are untouched, the
    last checkpoint is the one before the kill, byte for byte, and the run goes on from it to the
    uninterrupted run's history to 1e-12 (the same solves in the same order on one rank)."""
    mesh, _ = joint_small
    args = scene(mesh, tmp_path, "out", "1e-3", "-rom", "false", "-checkpoint_every", "5")
    run_boltrom(args)
    out = tmp_path / "out"
    before = {p.name: p.read_bytes() for p in (out / "paper-step.h5", out / "paper-step.xmf", out / "summary.json")}
    longer = scene(mesh, tmp_path, "out", "8e-3", "-rom", "false", "-checkpoint_every", "5")
    ckpt = out / "paper-step-fom.ckpt.h5"

    def past_step_20():
        with h5py.File(ckpt) as f:
            return int(f["/checkpoint/history"].attrs["step"]) >= 20
    at_kill = kill_while_written(longer, ckpt, past_step_20)
    for name, data in before.items():
        assert (out / name).read_bytes() == data, name
    assert ckpt.read_bytes() == at_kill
    with h5py.File(ckpt) as f:
        step = int(f["/checkpoint/history"].attrs["step"])
        # 15 counters, then per step 11 histories and the 5 pairs' forces (4 each)
        assert step >= 20 and step % 5 == 0 and len(f["/checkpoint/history"]) == 15 + (11 + 4 * 5) * (step + 1)
    p = run_boltrom(longer + ["-restart"])
    assert f"restarted from {ckpt} at step {step}" in p.stdout
    run_boltrom(scene(mesh, tmp_path, "whole", "8e-3", "-rom", "false", "-checkpoint_every", "5"))
    with h5py.File(out / "paper-step.h5") as f, h5py.File(tmp_path / "whole" / "paper-step.h5") as g:
        assert len(f["/fom/probe"]) == len(g["/fom/probe"]) == 81
        assert rel(g["/fom/probe"][...], f["/fom/probe"][...]) <= 1e-12
        assert rel(g["/fom/energy"][...], f["/fom/energy"][...]) <= 1e-12


def test_killed_rom_build_leaves_the_previous_rom_file(joint_small, tmp_path):
    """A ROM file of 20 + 20 interface vectors; a run that rebuilds it with 10 + 10 is killed while
    it writes the new file: the old one is unchanged byte for byte and is still reused by its scene."""
    mesh, _ = joint_small
    rom = tmp_path / "rom.h5"
    common = ["-mesh", mesh, "-fom", "false", "-ts_end", "1e-4", "-rom_file", rom, "-output", "false"]
    run_boltrom(SCENE + common)
    old = rom.read_bytes()
    kill_while_written(SCENE + common + ["-rom_n_ccm", "10", "-rom_n_jim", "10", "-rom_rebuild", rom], rom)
    assert rom.read_bytes() == old
    p = run_boltrom(SCENE + common)
    assert f"ROM: reusing {rom} (dimension" in p.stdout


def test_write_after_a_killed_write_does_not_wait(joint_small, tmp_path):
    """A run killed while it wrote rom.h5.tmp may leave Open MPI's semaphore for that file name
    taken (its shared-memory file pointer names it after the base name alone), and a later
    run writing the same name waited on it for ever. With such a semaphore planted, a ROM build on
    2 ranks into a file of that name finishes (in about 10 s) and its file is read back."""
    import ctypes
    mesh, _ = joint_small
    rom = tmp_path / "stale-rom.h5"
    name = f"/OMPIO_{rom.name}.tmp".encode()
    libc = ctypes.CDLL(None, use_errno=True)
    libc.sem_open.restype = ctypes.c_void_p
    sem = libc.sem_open(name, ctypes.c_int(0o100), ctypes.c_int(0o644), ctypes.c_uint(0))  # O_CREAT, taken
    assert sem not in (None, ctypes.c_void_p(-1).value), ctypes.get_errno()
    libc.sem_close(ctypes.c_void_p(sem))
    try:
        common = ["-mesh", mesh, "-fom", "false", "-ts_end", "1e-4", "-rom_file", rom, "-output", "false"]
        run_boltrom(SCENE + common, ranks=2, timeout=300)
        p = run_boltrom(SCENE + common)
        assert f"ROM: reusing {rom} (dimension" in p.stdout
    finally:
        libc.sem_unlink(name)


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


def test_mumps_short_of_workspace_is_factorised_again(joint_small, tmp_path):
    """MUMPS sizes its workspace from its analysis's estimate plus ICNTL(14) percent; on several
    ranks the estimate now and then falls short (INFOG(1) = -9), which PETSc records without
    raising, and every solve then returned Inf. A negative margin forces the same error on one
    rank: the interface reduction's factorisation is made again with a margin of 20 % (one line
    says so), and the ROM's history has the same bits as a run that never ran short."""
    mesh, _ = joint_small
    common = ["-options_file", ROOT / "inputs" / "paper-step.yaml", "-mesh", mesh, "-fom", "false", "-rom", "true",
              "-rom_file", "", "-rom_train", "none", "-ts_end", "0.002"]
    probe = {}
    for name, extra in (("plain", []), ("short", ["-ir_mat_mumps_icntl_14", "-50"])):
        d = tmp_path / name
        proc = run_boltrom(common + ["-output_dir", d] + extra)
        retries = [l for l in proc.stdout.splitlines() if l.startswith("MUMPS: the factorisation needed more workspace")]
        assert len(retries) == (1 if extra else 0), proc.stdout
        if extra:
            assert "INFOG(1) = -9" in retries[0] and "-ir_mat_mumps_icntl_14 20" in retries[0]
        with h5py.File(d / "paper-step.h5") as f:
            probe[name] = f["/rom/probe"][...]
    assert np.all(np.isfinite(probe["short"])) and np.array_equal(probe["plain"], probe["short"])
