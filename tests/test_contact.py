"""Contact and the full-order transient under the paper's contact law (-contact_law stick): patch
test, opening, energy, preload equilibrium, rank independence and non-convergence reporting. The
strict law, the default, has its own in test_strict.py."""
import h5py
import numpy as np
import pytest

from conftest import ROOT, assert_uniform_contact, make_mesh, run_boltrom, run_summary

FOM = ["-fom", "-static", "false", "-modal_nev", "0", "-contact_law", "stick"]


@pytest.fixture(scope="module")
def blocks(meshdir):
    return make_mesh("blocks", meshdir / "blocks.msh", 1)[0]


@pytest.mark.parametrize("penalty", ["1e2", "1e4", "1e6"])
def test_contact_patch_uniform_pressure(blocks, tmp_path, penalty):
    """Two blocks pressed by p = 1 kN / 1 cm^2 (nu = 0, so the exact stress is uniform): once the
    augmentations converge the traction is p at every Gauss point and the penetration vanishes."""
    s = run_summary(["-mesh", blocks] + FOM + ["-load_group", "top", "-probe_group", "top", "-load_force", "1000",
                     "-static_contact_load", "-ts_dt", "1e-4", "-ts_end", "1e-4", "-material_steel_nu", "0",
                     "-contact_penalty_factor", penalty, "-contact_tol_lambda", "1e-12", "-output", "false"], tmp_path)
    # penetration in metres: the penalty alone would leave p / eps
    assert_uniform_contact(s["preload"], 1000.0 / 1e-4, 1e-12)


def test_contact_opening(blocks, tmp_path):
    """The same blocks pulled apart: every point inactive, no contact force."""
    s = run_summary(["-mesh", blocks] + FOM + ["-load_group", "top", "-probe_group", "top", "-load_force", "1000",
                     "-load_direction", "0,0,1", "-ts_dt", "1e-5", "-ts_end", "5e-5", "-output", "false"], tmp_path)
    assert s["fom"]["active_points"] == 0
    assert s["fom"]["probe_final"] > 0  # the upper block moves up


def test_energy_conserved_and_dissipated(joint_small, tmp_path):
    """Undamped, beta = 1/4, pure penalty, active set fixed by the preload: the energy is
    constant to 1e-10 over 10^4 steps; with damping it never increases."""
    mesh, _ = joint_small
    # a wide activation band keeps the active set of this tiny load fixed: the premise of the test
    common = ["-mesh", mesh] + FOM + ["-contact_augment", "false", "-load_force", "0.1", "-ts_dt", "2e-5",
                                      "-contact_activation_gap", "1e-5", "-output_dir", tmp_path]
    s = run_summary(common + ["-ts_end", "0.2", "-rayleigh_alpha", "0", "-rayleigh_beta", "0"], tmp_path)
    assert s["fom"]["steps"] == 10000
    assert s["fom"]["factorizations"] == 1 and s["fom"]["outer_max"] == 1  # the active set never changed
    with h5py.File(tmp_path / "joint.h5") as f:
        e = f["/fom/energy"][1:]
    assert np.abs(e - e[0]).max() <= 1e-10 * np.abs(e).max()
    run_summary(common + ["-ts_end", "0.01"], tmp_path, name="damped")
    with h5py.File(tmp_path / "joint.h5") as f:
        e = f["/fom/energy"][1:]
    assert np.all(np.diff(e) <= 1e-12 * np.abs(e).max())
    assert e[-1] < e[0]


def test_preload_equilibrium(joint_small, tmp_path):
    mesh, _ = joint_small
    s = run_summary(["-mesh", mesh] + FOM + ["-ts_dt", "1e-4", "-ts_end", "1e-4", "-contact_tol_lambda", "1e-7", "-contact_max_inner", "1000",
                     "-output", "false"], tmp_path)
    forces = s["preload"]["normal_force_per_pair"]
    assert len(forces) == 5
    for pair, f in forces.items():
        assert abs(-f / 20000.0 - 1) < 1e-6, (pair, f)


def test_fom_history_same_on_1_and_2_ranks(joint_small, tmp_path):
    mesh, _ = joint_small
    hist = {}
    for ranks in (1, 2):
        d = tmp_path / f"np{ranks}"
        run_summary(["-mesh", mesh] + FOM + ["-ts_dt", "1e-4", "-ts_end", "5e-3", "-contact_tol_lambda", "1e-9", "-contact_max_inner", "1000",
                     "-output_dir", d], d, ranks=ranks)
        with h5py.File(d / "joint.h5") as f:
            hist[ranks] = f["/fom/probe"][...]
    assert np.abs(hist[1] - hist[2]).max() <= 1e-8 * np.abs(hist[1]).max()


def test_non_convergence_is_reported(joint_small, tmp_path):
    mesh, _ = joint_small
    args = ["-mesh", mesh] + FOM + ["-ts_dt", "1e-4", "-ts_end", "5e-4", "-contact_max_inner", "1",
                                    "-output_dir", tmp_path / "out"]
    proc = run_boltrom(args, check=False)
    assert proc.returncode != 0
    line = proc.stderr.strip().splitlines()
    assert len(line) == 1 and "did not converge at step 0, t = 0" in line[0] and "multipliers change" in line[0]
    assert "-contact_max_inner" in line[0] and "-contact_continue" in line[0]
    assert not (tmp_path / "out").exists()
    proc = run_boltrom(args + ["-contact_continue"], check=True)
    assert "WARNING FOM: augmentations not converged at step" in proc.stdout


def test_fom_converges_where_the_load_opens_the_joint(joint_small, tmp_path):
    """10 kN at the tip opens a good part of the joint. The inner CG needs more than 500 iterations
    there, and a limit of 500 stopped the loop at step 5 while it was still converging: the limit
    was too tight. With the default limit (5000) it converges; a limit of 500 still stops with the
    message."""
    mesh, _ = joint_small
    args = ["-mesh", mesh] + FOM + ["-ts_dt", "1e-4", "-ts_end", "6e-4", "-load_force", "10000"]
    s = run_summary(args + ["-output_dir", tmp_path / "a"], tmp_path / "a", ranks=2)
    f = s["fom"]
    assert f["failures"] == 0 and f["inner_max"] > 500, f
    assert f["active_points"] <= 0.75 * f["contact_points"], f  # the load opens part of the joint
    proc = run_boltrom(args + ["-contact_max_inner", "500", "-output_dir", tmp_path / "b"], check=False, ranks=2)
    assert proc.returncode != 0 and "did not converge at step 5" in proc.stderr
    assert not (tmp_path / "b").exists()


def test_snapshot_series_for_paraview(joint_small, tmp_path):
    """The series holds the displacement and the contact state at each snapshot; the last equals
    the final fields. The state is 1 + the state of most of a node's contact points (1 open,
    2 stick), 0 off the contact: every node of the five pairs has points, and the preloaded joint
    under its load is open at its rim only."""
    import xml.etree.ElementTree as ET
    mesh, info = joint_small
    run_summary(["-mesh", mesh] + FOM + ["-ts_dt", "1e-4", "-ts_end", "1e-3", "-snapshot_every", "5",
                 "-output_dir", tmp_path], tmp_path)
    root = ET.parse(tmp_path / "joint-series.xmf").getroot()
    times = [float(t.get("Value")) for t in root.iter("Time")]
    assert np.allclose(times, [0, 5e-4, 1e-3])
    with h5py.File(tmp_path / "joint.h5") as f:
        for item in root.iter("DataItem"):
            fname, path = item.text.strip().split(":")
            assert f[path].shape == tuple(int(v) for v in item.get("Dimensions").split())
        last = f["/vertex_fields/snapshot_000002"][...]
        assert np.allclose(last, f["/vertex_fields/fom_final_displacement"][...])
        state = f["/vertex_fields/fom_final_contact_state"][...].ravel()
        assert np.array_equal(state, f["/vertex_fields/contact_state_000002"][...].ravel())
    assert [a.get("Name") for a in root.iter("Attribute") if a.get("Name") != "part"] == ["displacement", "contact_state"] * 3
    counts = np.bincount(state.astype(int), minlength=4)
    assert counts[1:].sum() == info["contact_dofs"] // 3
    assert counts[3] == 0 and 0 < counts[1] < 0.2 * counts[2], counts  # no slip without friction; a few open


def test_converged_contact_does_not_depend_on_the_penalty(joint_small, tmp_path):
    """Augmented Lagrangian: once the multipliers converge the gaps are closed, so the response
    does not depend on the penalty. Regression (scripts/stress): the opening band scaled with
    eps_N, and under a stiff penalty it kept every point closed."""
    mesh, _ = joint_small
    hist = {}
    for pf in ("1e3", "1e4"):
        d = tmp_path / pf
        s = run_summary(["-mesh", mesh] + FOM + ["-options_file", ROOT / "inputs" / "paper-step.yaml", "-rom", "false",
                         "-ts_dt", "1e-4", "-ts_end", "5e-3", "-contact_penalty_factor", pf, "-output_dir", d], d)
        assert s["fom"]["failures"] == 0
        with h5py.File(d / "paper-step.h5") as f:
            hist[pf] = f["/fom/probe"][...]
    assert np.linalg.norm(hist["1e3"] - hist["1e4"]) <= 1e-4 * np.linalg.norm(hist["1e4"])


PAPER_SCENE = ["-element", "incompatible", "-preload_force", "20000", "-load_group", "load_point",
               "-load_direction", "0,0,-1", "-load_force", "10", "-probe_group", "load_point",
               "-probe_component", "2", "-contact_penalty_factor", "200"]


def test_active_set_settles_in_the_preload(joint_paper, tmp_path):
    """The paper's preloaded joint: the active set is settled by the static preload, in few outer
    iterations, and the first transient steps keep it. Two faults made this fail (level 1: 7 outer
    iterations at step 1; level 1.8: not settled in 20 or 100): the band was judged on the
    tractions before the clamping-force calibration (x15), and a point opened on its own
    Gauss-point multiplier, whose forceless part (four multipliers per node) reads tens of MPa
    of tension over nodes in compression at the edge of the contact zone."""
    mesh, _ = joint_paper
    args = ["-mesh", mesh] + FOM + PAPER_SCENE + ["-ts_dt", "1e-4", "-ts_end", "3e-4", "-contact_max_outer", "4",
                                                  "-output", "false"]
    s = run_summary(args, tmp_path)
    assert s["preload"]["outer"] <= 3
    assert s["fom"]["outer_max"] == 1 and s["fom"]["factorizations"] == 1  # steps 1-3 keep the preload's set
    assert s["fom"]["cycles"] == 0  # settled without the anti-cycling rule
    # the points under the washers (nodal compression 3-49 MPa) stay closed; only the plates'
    # interface near the overlap square's edge opens
    assert s["preload"]["active_points"] >= 2100  # the old test left 1968 of 2112
    # the old opening test on the multiplier at each Gauss point creeps inwards (the anti-cycling
    # rule, which would stop the creep by letting points only close, is off here)
    proc = run_boltrom(args + ["-contact_open_test", "gauss", "-contact_cycle_close", "false", "-summary", tmp_path / "gauss.json"], check=False)
    assert proc.returncode != 0 and "the active set did not settle at step 0" in proc.stderr


def test_contact_sides_counted_on_any_partition(joint_small, tmp_path):
    """A vertex on the rim of a contact side can be owned by a rank that holds none of the side's
    faces, only a neighbouring cell. Regression: such vertices were counted by no rank, so a
    partition-dependent mesh check refused a valid mesh (scripts/stress, level 0.7: 'side a has
    60 nodes but side b has 64'). The 'simple' partition of the coarse joint on 3 ranks
    reproduced it every time (plate2_plate1: 59 against 64 nodes). The same run must give the
    1-rank contact DOFs and history."""
    mesh, info = joint_small
    args = ["-mesh", mesh] + FOM + ["-options_file", ROOT / "inputs" / "paper-step.yaml", "-rom", "false",
                                    "-ts_dt", "1e-4", "-ts_end", "5e-4", "-output_name", "run",
                                    # a tight loop, so that the histories differ by round-off only
                                    # (at the default 1e-4 they differed by 2.8e-8 once in CI)
                                    "-contact_tol_lambda", "1e-9", "-contact_max_inner", "1000"]
    s1 = run_summary(args + ["-output_dir", tmp_path / "r1"], tmp_path / "r1", ranks=1)
    s3 = run_summary(args + ["-output_dir", tmp_path / "r3", "-partitioner", "simple"], tmp_path / "r3", ranks=3)
    assert s3["contact_dofs"] == s1["contact_dofs"] == info["contact_dofs"]
    with h5py.File(tmp_path / "r1" / "run.h5") as f1, h5py.File(tmp_path / "r3" / "run.h5") as f3:
        h1, h3 = f1["/fom/probe"][...], f3["/fom/probe"][...]
    assert np.linalg.norm(h3 - h1) <= 1e-8 * np.linalg.norm(h1)
