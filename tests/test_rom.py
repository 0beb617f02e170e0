"""The reduced-order model under the paper's contact law (-contact_law stick): the Krylov basis
(unit checks), exactness of contact as a low-rank input at s0, accuracy against the FOM,
interface reduction, and rank independence. The ROM under the strict law, the default, is in
test_strict.py and test_reference.py."""
import json
import math
import re
import subprocess
from pathlib import Path

import h5py
import numpy as np
import pytest

from conftest import ENV, ROOT, run_summary

ROM = ["-static", "false", "-modal_nev", "0", "-contact_law", "stick", "-rom"]
# the paper's IR ROM (CCM + JIM 100 + 100, order 1) on the first 100 steps of paper-step
PAPER_ROM = ROM + ["-rom_n_ccm", "100", "-rom_n_jim", "100", "-krylov_order", "1", "-ts_dt", "1e-4", "-ts_end", "0.01"]


@pytest.mark.parametrize("ranks", [1, 2])
def test_krylov_unit_checks(ranks):
    """Orthonormality (orders 1-4, 8), moment matching (orders 1-3, and the next moment does
    not match), deflation of duplicated and zero columns, 1 vs all ranks: tests/c/test_krylov.c."""
    cmd = ([] if ranks == 1 else ["mpiexec", "-n", str(ranks)]) + [str(ROOT / "bin" / "test_krylov")]
    proc = subprocess.run(cmd, capture_output=True, text=True, env=ENV, timeout=600)
    lines = [l for l in proc.stdout.splitlines() if l.startswith(("PASS", "FAIL"))]
    assert proc.returncode == 0 and lines and not any(l.startswith("FAIL") for l in lines), proc.stdout + proc.stderr


@pytest.mark.parametrize("ranks", [1, 2, 3])
def test_exact_sums_over_ranks(ranks, tmp_path):
    """The reduced model's sums over ranks (BoltExactSum, tests/c/test_exact_sum.c): five columns
    of 4000 dyadic terms built to cancel (pairs +a, -a of magnitudes 2^-72 to 1, near pairs,
    small terms, two exact ties), shuffled, summed in order, reversed, round-robin and in sorted
    blocks over the ranks, with partials kept and put back, and with terms replaced in place:
    each result is, bit for bit, the exact sum (an __int128 count of 2^-72) rounded to the
    nearest double, ties to even; the plain double sum is not (off by 0.35 in one column). Here
    the split sums are also held to Python's math.fsum of the terms the program wrote (a
    correctly rounded sum computed apart from the C code), so every rank count gives the same bits."""
    terms = tmp_path / "terms.txt"
    cmd = ([] if ranks == 1 else ["mpiexec", "-n", str(ranks)]) + [str(ROOT / "bin" / "test_exact_sum"), "-terms", str(terms)]
    proc = subprocess.run(cmd, capture_output=True, text=True, env=ENV, timeout=300)
    lines = [l for l in proc.stdout.splitlines() if l.startswith(("PASS", "FAIL"))]
    assert proc.returncode == 0 and len(lines) == 10 and not any(l.startswith("FAIL") for l in lines), proc.stdout + proc.stderr
    columns = list(zip(*([float.fromhex(v) for v in l.split()] for l in terms.read_text().splitlines())))
    sums = [float.fromhex(l.split()[2]) for l in proc.stdout.splitlines() if l.startswith("SUM")]
    assert len(columns) == len(sums) == 5 and all(len(c) == 4000 for c in columns)
    for column, got in zip(columns, sums):
        assert got.hex() == math.fsum(column).hex()
    # the columns as built: an exact zero, two ties rounded to even, heavy cancellation
    assert sums[0] == 0 and sums[2] == 2.0**-10 and sums[3] == 2.0**-10 + 2.0**-61 and sums[4] < 0
    # the largest term over the sum: 1.5e13 in column 4 (44 bits cancel), 4.9e6 in column 1
    assert max(abs(x) for x in columns[4]) / abs(sums[4]) > 1e13 and max(abs(x) for x in columns[1]) / abs(sums[1]) > 1e6


@pytest.mark.parametrize("order", [1, 2])
def test_contact_as_low_rank_input_is_exact_at_s0(joint_small, tmp_path, order):
    """Tied joint, (s0^2 M + s0 C + K + K_c) q = f: the ROM without interface reduction
    (K_cr = V' K_c V) reproduces it to 1e-8; its basis is orthonormal to 1e-12: the Krylov
    vectors, then the five static shapes (preloaded state, load response, three closed-contact
    Krylov vectors). Both checks are -rom_verify's, which also refactorises at every change."""
    mesh, _ = joint_small
    s = run_summary(["-mesh", mesh] + ROM + ["-rom_n_ccm", "0", "-rom_n_jim", "0", "-krylov_order", order,
                     "-rom_verify", "-ts_dt", "1e-4", "-ts_end", "2e-4",
                     "-output", "false"], tmp_path)
    assert s["rom"]["check_s0_error"] < 1e-8
    assert s["rom"]["orthogonality"] < 1e-12
    assert s["rom"]["dim"] == order * s["rom"]["inputs"] + 5 and s["rom"]["closed_krylov"] == 3
    assert s["rom"]["update_rank"] == 0 and s["rom"]["low_rank_updates"] == 0


@pytest.mark.parametrize("order", ["2", "1"])
def test_rom_matches_fom_without_interface_reduction(joint_small, tmp_path, order):
    """The paper's ROM without interface reduction (its Table 3: 7.8e-4), to 1e-3 at orders 1
    and 2. At order 1 the static shapes (the closed joint's static responses to the load and to
    the mass times them) carry its inertia: without them it was of order 1 off (docs/reduction.md,
    static shapes)."""
    mesh, _ = joint_small
    # a wide activation band keeps the active set fixed in both models, so that the comparison
    # measures the reduction and not the edge-of-contact decisions (docs/reduction.md: both are reported)
    s = run_summary(["-mesh", mesh, "-fom"] + ROM + ["-rom_n_ccm", "0", "-rom_n_jim", "0", "-krylov_order", order,
                     "-contact_activation_gap", "1e-5", "-ts_dt", "1e-4", "-ts_end", "0.01",
                     "-output", "false"], tmp_path)
    e = s["errors"]["load_point"]
    print(f"ROM (order {order}, no interface reduction) against FOM:", e, "dim", s["rom"]["dim"])
    assert e["e_L2"] < 1e-3 and s["rom"]["dim"] == int(order) * s["rom"]["inputs"] + 5


def test_rom_with_interface_reduction(joint_small, tmp_path):
    """CCM + JIM: the interface basis is orthonormal, the ROM is small, and it follows the FOM."""
    mesh, _ = joint_small
    s = run_summary(["-mesh", mesh, "-fom"] + ROM + ["-rom_n_ccm", "100", "-rom_n_jim", "100", "-krylov_order", "2",
                     "-rom_verify", "-ts_dt", "1e-4", "-ts_end", "0.01", "-output", "false"], tmp_path)
    r = s["rom"]
    print("ROM (CCM+JIM 100+100, order 2) against FOM:", s["errors"]["load_point"], "dim", r["dim"])
    assert 0 < r["n_ccm"] <= 100 and 0 < r["n_jim"] <= 100
    # the Krylov vectors, then the FOM's preloaded displacement, its closed-contact load response
    # and three closed-contact Krylov vectors
    assert r["inputs"] == r["n_ccm"] + r["n_jim"] + 2 and r["dim"] <= 2 * r["inputs"] + 5
    assert r["orthogonality"] < 1e-12
    # fewer reduced DOFs than contact constraints: the reduced dual loop uses the penalty law
    assert r["contact_law"] == "penalty" and r["failures"] == 0
    assert r["preload_state"] == 1 and r["closed_krylov"] == 3 and r["contact_penalty_scale"] == 500 and r["contact_band_scale"] == 1
    assert s["errors"]["load_point"]["e_L2"] < 3e-4  # offline static solves at the FOM's own penalty give about 4e-4 here (docs/decisions.md)


def test_rom_starts_from_the_foms_preloaded_state(joint_small, tmp_path):
    """The interface-reduced ROM starts where the FOM does (the FOM run's preloaded state: q0 in the basis,
    multipliers frozen), its order-1 history follows the FOM, and the preloaded state stored in
    the ROM file serves another partition (2 ranks write it, 1 and 3 ranks read it)."""
    mesh, _ = joint_small
    common = ["-mesh", mesh] + PAPER_ROM
    rom_file = tmp_path / "joint.rom.h5"
    d = tmp_path / "np2"
    s = run_summary(common + ["-fom", "-rom_file", rom_file, "-output_dir", d], d, ranks=2)
    with h5py.File(d / "joint.h5") as f:
        fom, rom = f["/fom/probe"][...], f["/rom/probe"][...]
        ledger = {m: {k: f[f"/{m}/energy_accounting/{k}"][...] for k in ("balance", "external_work")} for m in ("fom", "rom")}
    scale = np.abs(fom).max()
    # The multipliers stay frozen through the transient: the ROM's ledger balances (measured 2.6e-5
    # of the load's work) and the load does the FOM's work on it (0.46 %). Dropped after the static
    # solve, the joint lost its clamp force at the first step: 12 % of the work unaccounted for,
    # and 13 % more work done (paper-step's options, level 0.5).
    work = np.abs(ledger["fom"]["external_work"]).max()
    print("ROM ledger: balance", np.abs(ledger["rom"]["balance"]).max() / work, "of the work; its work off the FOM's by",
          np.abs(ledger["rom"]["external_work"] - ledger["fom"]["external_work"]).max() / work)
    assert np.abs(ledger["rom"]["balance"]).max() <= 1e-3 * work
    assert np.abs(ledger["rom"]["external_work"] - ledger["fom"]["external_work"]).max() <= 0.02 * work
    print("preloaded probe: FOM", fom[0], "ROM", rom[0], "; e_L2", s["errors"]["load_point"]["e_L2"])
    # the penalty law alone started 7 times further down (docs/decisions.md). The offline phase takes the FOM
    # run's own preloaded state, so the start is the FOM's to the round-off of the reduced system
    # under its near-hard penalty (solving it again instead moved the start far more than this bound)
    assert abs(rom[0] - fom[0]) <= 1e-7 * scale
    assert s["errors"]["load_point"]["e_L2"] < 1.5e-3  # well inside the paper's 3.5e-3 at its level; current figure in docs/results.md
    from_file = {}
    for ranks in (1, 3):
        d = tmp_path / f"np{ranks}"
        s = run_summary(common + ["-rom_file", rom_file, "-output_dir", d, "-partitioner", "simple"], d, ranks=ranks)
        assert s["rom"]["source"] == "file"
        with h5py.File(d / "joint.h5") as f:
            from_file[ranks] = f["/rom/probe"][...]
        # a state matched to the wrong elements is off by percents; the file's state (per newton of
        # preload) against the building run's own differs by round-off only (the 2-rank build's
        # partition is PT-Scotch's, not repeatable, so the bound is not zero)
        print(ranks, "ranks: largest difference from the building run", np.abs(from_file[ranks] - rom).max() / scale)
        assert np.abs(from_file[ranks] - rom).max() <= 1e-9 * scale, ranks
    # The reduced sums over ranks are exact (BoltExactSum), so no round-off is left for the
    # near-hard penalty (condition number ~1e9) to lift: one file gives the same bits on 1 and 3
    # ranks. With ordinary floating-point sums they were not (docs/reduction.md)
    assert np.array_equal(from_file[1], from_file[3])


def test_rom_history_same_on_1_and_2_ranks(joint_small, tmp_path):
    """The ROM without interface reduction built on 1 and on 2 ranks: the same dimension, and
    histories within a stated margin of their measured difference (2.83e-4; two 2-rank runs:
    2.5e-8). One static shape lies within 4.6e-11 of its norm of the Krylov vectors' span and is
    kept; orthogonalising it scales the builds' round-off up by about 1/4.6e-11, and the
    histories then part by 1.5e-6 of the response after one step, 2.83e-4 after 50, the same in
    every run (without the static shapes the builds agreed to 1.5e-10). The bound catches the
    mass matrix assembled without the entries a rank adds to rows the other owns (6.0e-4). From
    one ROM file the histories agree to 1e-8 (test_rom_file_built_on_2_ranks_serves_1_rank)."""
    mesh, _ = joint_small
    hist, dim = {}, {}
    for ranks in (1, 2):
        d = tmp_path / f"np{ranks}"
        s = run_summary(["-mesh", mesh] + ROM + ["-rom_n_ccm", "0", "-rom_n_jim", "0", "-ts_dt", "1e-4", "-ts_end", "5e-3",
                         "-contact_tol_lambda", "1e-9", "-contact_max_inner", "1000",
                         "-output_dir", d], d, ranks=ranks)
        dim[ranks] = s["rom"]["dim"]
        with h5py.File(d / "joint.h5") as f:
            hist[ranks] = f["/rom/probe"][...]
    assert dim[1] == dim[2] == 775, dim
    diff = np.abs(hist[1] - hist[2]).max() / np.abs(hist[1]).max()
    print(f"1 against 2 ranks {diff:.3e} of the response")
    assert diff <= 4e-4


def test_rom_file_reuse_and_refusal(joint_small, tmp_path):
    """One ROM file serves two load amplitudes without rebuilding; a changed material, friction
    coefficient or stick stiffness is refused with the first difference and the file kept byte for
    byte, or with -rom_rebuild FILE the ROM is built into FILE; a load that is not an input is
    refused unless the user opts in."""
    from conftest import run_boltrom
    mesh, _ = joint_small
    rom_file = tmp_path / "joint.rom.h5"
    base = ["-mesh", mesh] + ROM + ["-ts_dt", "1e-4", "-ts_end", "1e-3", "-output", "false", "-rom_file", rom_file,
                                      "-rom_n_ccm", "0", "-rom_n_jim", "0", "-contact_tol_lambda", "1e-8", "-contact_max_inner", "2000"]
    a = run_summary(base + ["-load_force", "10"], tmp_path, name="a")
    b = run_summary(base + ["-load_force", "20"], tmp_path, name="b")
    assert a["rom"]["source"] == "built" and b["rom"]["source"] == "file"
    assert b["rom"]["offline_basis_s"] == 0 and b["rom"]["dim"] == a["rom"]["dim"]
    # the reused file answers as a ROM built for 20 N does
    fresh = run_summary([x if x != rom_file else tmp_path / "fresh.h5" for x in base] + ["-load_force", "20"], tmp_path, name="fresh")
    assert fresh["rom"]["source"] == "built"
    assert abs(b["rom"]["probe_final"] - fresh["rom"]["probe_final"]) <= 1e-8 * abs(fresh["rom"]["probe_final"])
    kept = rom_file.read_bytes()
    for change, words in ((["-material_steel_E", "200e9"], ["part_bolt_E: the file has 2.1e+11, the scene 2e+11"]),
                          (["-contact_law", "coulomb", "-contact_friction", "0.2"], ["contact_law: the file has 'stick', the scene 'coulomb'"])):
        proc = run_boltrom(base + change + ["-output_dir", tmp_path / "x"], check=False)
        lines = [l for l in proc.stderr.splitlines() if l.strip()]
        assert proc.returncode != 0 and len(lines) == 1 and "was built for another scene" in lines[0], proc.stderr
        assert all(w in lines[0] for w in words) and "-rom_rebuild FILE" in lines[0], lines[0]
        assert "FOM" not in proc.stdout and rom_file.read_bytes() == kept  # refused before any model runs
    c = run_summary(base + ["-material_steel_E", "200e9", "-rom_rebuild", rom_file], tmp_path, name="c")  # overwritten on purpose
    assert c["rom"]["source"] == "built"
    proc = run_boltrom(base + ["-material_steel_E", "200e9", "-load_group", "corner_point", "-probe_group", "corner_point"], check=False)
    assert proc.returncode != 0 and "-rom_allow_foreign_load" in proc.stderr
    d = run_summary(base + ["-material_steel_E", "200e9", "-load_group", "corner_point", "-probe_group", "corner_point",
                            "-rom_allow_foreign_load"], tmp_path, name="d")
    assert d["rom"]["source"] == "file"


def test_rom_file_built_on_2_ranks_serves_1_rank(joint_small, tmp_path):
    """The ROM file keys its rows by partition-independent DOF keys, so a file built on 2 ranks
    (PT-Scotch partition) is read by a 1-rank run, which skips the offline phase and gives the
    same history; a contact row missing from the file would be an error, never a silent zero."""
    mesh, _ = joint_small
    rom_file = tmp_path / "joint.rom.h5"
    base = ["-mesh", mesh] + ROM + ["-ts_dt", "1e-4", "-ts_end", "2e-3", "-rom_file", rom_file, "-rom_n_ccm", "0",
                                      "-rom_n_jim", "0", "-contact_tol_lambda", "1e-9", "-contact_max_inner", "1000"]
    hist = {}
    for ranks in (2, 1):
        d = tmp_path / f"np{ranks}"
        s = run_summary(base + ["-output_dir", d], d, ranks=ranks)
        assert s["rom"]["source"] == ("built" if ranks == 2 else "file")
        with h5py.File(d / "joint.h5") as f:
            hist[ranks] = f["/rom/probe"][...]
    assert np.abs(hist[1] - hist[2]).max() <= 1e-8 * np.abs(hist[2]).max()


def petsc_aij(path):
    """A matrix PETSc wrote in its binary format (MatView, sequential AIJ layout: class id, rows,
    columns, nonzeros, then row lengths, column indices and values, big-endian) as scipy CSR."""
    import scipy.sparse
    b = Path(path).read_bytes()
    _, m, n, nz = np.frombuffer(b, ">i4", 4)
    lengths = np.frombuffer(b, ">i4", m, 16)
    cols = np.frombuffer(b, ">i4", nz, 16 + 4 * m)
    vals = np.frombuffer(b, ">f8", nz, 16 + 4 * (m + nz))
    ptr = np.concatenate([[0], np.cumsum(lengths)])
    return scipy.sparse.csr_matrix((vals.astype(float), cols.astype(np.int64), ptr), shape=(m, n))


def test_eigenfrequencies_full_and_reduced(joint_small, tmp_path):
    """The tied joint's first five eigenfrequencies. The reference: the exported K_tied and M
    solved by scipy (ARPACK, shift-invert by SuperLU), independent of boltrom's SLEPc and MUMPS.
    boltrom's FOM frequencies equal it to 1e-9 (measured 1.1e-11 in the summary), and so do those of
    python/compare_eigen.py to its printed digits. The ROM's, by a dense LAPACK solve of its
    exported matrices: without interface reduction (the basis holds every contact DOF's
    response) f1 within 1e-7 (measured 1.3e-8); the paper's CCM + JIM 100 + 100 (dimension 150)
    f1 within 2.5e-3 (1.94e-3) and f3 within 2e-2 (1.57e-2)."""
    import scipy.linalg
    import scipy.sparse.linalg
    from conftest import PYTHON
    mesh, _ = joint_small
    rom = {}
    for ccm_jim in (0, 100):
        d = tmp_path / f"ir{ccm_jim}"
        s = run_summary(["-mesh", mesh, "-modal_nev", "5", "-contact_law", "stick", "-rom", "-rom_n_ccm", ccm_jim,
                         "-rom_n_jim", ccm_jim, "-ts_end", "2.5e-4", "-export_matrices", d, "-output", "false"], tmp_path,
                        name=f"ir{ccm_jim}")
        K, M = petsc_aij(d / "rom_K_tied.petsc").toarray(), petsc_aij(d / "rom_M.petsc").toarray()
        lam = scipy.linalg.eigh(0.5 * (K + K.T), 0.5 * (M + M.T), eigvals_only=True)
        rom[ccm_jim] = np.sqrt(lam[:5]) / (2 * np.pi)
    K, M = petsc_aij(d / "K_tied.petsc").tocsc(), petsc_aij(d / "M.petsc").tocsc()
    lam = scipy.sparse.linalg.eigsh(K, 8, M, sigma=0.0, which="LM", tol=1e-13, return_eigenvectors=False)
    ref = np.sqrt(np.sort(lam)[:5]) / (2 * np.pi)
    own = np.array(s["modal"]["frequencies_hz"])
    print("reference", ref, "boltrom", own / ref - 1, "ROM 0+0", rom[0] / ref - 1, "ROM 100+100", rom[100] / ref - 1)
    assert np.abs(own / ref - 1).max() <= 1e-9
    out = subprocess.run([PYTHON, str(ROOT / "python" / "compare_eigen.py"), str(d), "5"], env=ENV, capture_output=True,
                         text=True, check=True)
    rows = [l.split("|") for l in out.stdout.splitlines()[2:]]
    assert len(rows) == 5
    assert np.abs(np.array([float(r[2]) for r in rows]) - ref).max() <= 5e-4     # printed to 1e-3 Hz
    assert np.abs(np.array([float(r[3]) for r in rows]) - rom[100]).max() <= 5e-4
    assert abs(rom[0][0] / ref[0] - 1) <= 1e-7
    err = rom[100] / ref - 1
    assert abs(err[0]) <= 2.5e-3 and abs(err[2]) <= 2e-2, err


def test_rom_under_a_small_load(joint_small, tmp_path):
    """0.1 N at the tip, 2e5 times below the preload. The offline load response and closed-contact
    Krylov vectors are static solves from the preloaded state, converged to a tolerance relative to
    the preload's multipliers; forced at 0.1 N their shapes were mostly that residual, and the ROM
    was more than 1 % off. They are forced at 1e-3 of the preload's norm at least (far above the
    load here), and the ROM must be within 1 % (docs/reduction.md, preloaded state)."""
    from conftest import run_boltrom
    mesh, _ = joint_small
    args = ["-mesh", mesh] + PAPER_ROM + ["-fom", "-load_force", "0.1", "-output_dir", tmp_path / "a", "-summary", tmp_path / "a.json"]
    proc = run_boltrom(args, ranks=2)
    s = json.loads((tmp_path / "a.json").read_text())
    raised = float(re.search(r"load response \(load x (\S+)\)", proc.stdout).group(1))
    force, preload = (float(x) for x in re.search(r"closed-contact Krylov forcing of norm (\S+) \(load \S+, preload (\S+)\)", proc.stdout).groups())
    assert raised == pytest.approx(1e-3 * preload / 0.1, rel=1e-6) and force == pytest.approx(1e-3 * preload, rel=1e-6)
    print("0.1 N: e_L2", s["errors"]["load_point"]["e_L2"])
    assert s["errors"]["load_point"]["e_L2"] < 0.01


def test_closed_contact_vectors_keep_the_preloaded_active_set(joint_small, tmp_path):
    """The closed-contact Krylov vectors are shapes of the joint as preloaded. Their forcing (the
    mass times the previous vector) is spread over the whole volume; free to change the active
    set, it opened rim points on fine meshes, and the basis of that opened joint was less
    accurate (docs/decisions.md). Here every vector ends with the preloaded count of closed
    points in one outer iteration."""
    from conftest import run_boltrom
    mesh, _ = joint_small
    d = tmp_path / "keep"
    proc = run_boltrom(["-mesh", mesh] + PAPER_ROM + ["-fom", "-output_dir", d, "-output_name", "run", "-summary", d / "s.json"])
    preloaded = int(re.search(r"iterations, (\d+) of \d+ points closed", proc.stdout).group(1))
    vectors = [(int(float(o)), int(n)) for o, n in
               re.findall(r"closed-contact Krylov vector \d+: (\S+) outer / \S+ inner iterations, (\d+) points closed", proc.stdout)]
    print("preloaded", preloaded, "vectors", vectors)
    assert len(vectors) == 3 and all(o == 1 and n == preloaded for o, n in vectors)


def test_rom_where_the_load_opens_the_joint(joint_small, tmp_path):
    """A 1 kN load opens the joint over most of the overlap (704 active points down to about 110).
    Two rules found by the stress sweep (docs/reduction.md, docs/model.md): the offline closed-contact Krylov solves are forced at
    1e-3 of the preload's norm, not at the load's, which opened the joint and stopped the build;
    and the reduced dual loop's active set, which cycled here, is made to settle by letting points
    only close for the rest of a step once it cycles. Without the second the same ROM file stops."""
    from conftest import run_boltrom
    mesh, _ = joint_small
    rom_file = tmp_path / "joint.rom.h5"
    base = ["-mesh", mesh] + PAPER_ROM + ["-load_force", "1000", "-rom_file", rom_file]
    proc = run_boltrom(base + ["-fom", "-output_dir", tmp_path / "a", "-summary", tmp_path / "a.json"])
    s = json.loads((tmp_path / "a.json").read_text())
    line = [l for l in proc.stdout.splitlines() if l.startswith("ROM: closed-contact Krylov forcing")][0]
    force, load, preload = (float(x) for x in re.match(r"ROM: closed-contact Krylov forcing of norm (\S+) \(load (\S+), preload (\S+)\)", line).groups())
    assert load == pytest.approx(1000) and force == pytest.approx(1e-3 * preload, rel=1e-6) and force < load
    assert s["fom"]["failures"] == 0 and s["rom"]["failures"] == 0
    assert s["rom"]["cycles"] > 0  # the anti-cycling rule was needed (docs/model.md, dual loop)
    print("1 kN: e_L2", s["errors"]["load_point"]["e_L2"], "cycles", s["rom"]["cycles"])
    assert s["errors"]["load_point"]["e_L2"] < 0.025  # where the load opens the joint the IR ROM is 1-2 % off, varying from build to build (docs/results.md)
    proc = run_boltrom(base + ["-fom", "false", "-contact_cycle_close", "false", "-output_dir", tmp_path / "b"], check=False)
    # it either cycles or runs out of outer iterations (it cycled with the FOM's activation band)
    assert proc.returncode != 0 and "the active set did not settle" in proc.stderr
    assert not (tmp_path / "b" / "joint.h5").exists()
