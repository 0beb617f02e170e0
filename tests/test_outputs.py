"""What a run writes and what it refuses before it writes: a vector option with the wrong number
of components or a non-finite one stops the run before the mesh is read; the result file's root
attributes (units, probe, load, contact law, friction per pair, options) and the JSON summary's
load and friction fields; the ROM's displacement field (V q), at the snapshots and at the end."""
import json

import h5py
import numpy as np
import pytest

from conftest import make_mesh, run_boltrom


@pytest.fixture(scope="module")
def beam(meshdir):
    return make_mesh("beam", meshdir / "beam-outputs.msh", 0.5)[0]


def expect_one_line_error(args, tmp_path):
    out = tmp_path / "out"
    proc = run_boltrom(list(args) + ["-output_dir", out, "-summary", out / "summary.json"], check=False)
    assert proc.returncode != 0
    lines = [l for l in proc.stderr.splitlines() if l.strip()]
    assert len(lines) == 1 and lines[0].startswith("boltrom: error: "), proc.stderr
    assert not out.exists() or not any(out.iterdir())
    return lines[0]


@pytest.mark.parametrize("option", ["-load_direction", "-preload_axis"])
@pytest.mark.parametrize("value,count", [("1,0", "2 components"), ("1", "1 component"), ("1,0,0,1", "4 components")])
def test_vector_option_with_wrong_count_is_refused_before_the_mesh(tmp_path, option, value, count):
    """A mesh that does not exist: the vector is refused first, so the check comes before the
    mesh is read; the line names the option, what was given and what is expected."""
    line = expect_one_line_error(["-mesh", tmp_path / "absent.msh", option, value], tmp_path)
    assert f"{option} {value}:" in line and count in line and "3 expected" in line and "comma-separated" in line, line
    assert "absent.msh" not in line


@pytest.mark.parametrize("option", ["-load_direction", "-preload_axis"])
@pytest.mark.parametrize("value,which", [("1,nan,0", 2), ("inf,0,1", 1), ("0,0,-INF", 3), ("0,x,1", 2), ("1,,0", 2)])
def test_vector_option_not_finite_is_refused(tmp_path, option, value, which):
    line = expect_one_line_error(["-mesh", tmp_path / "absent.msh", option, value], tmp_path)
    assert f"{option} {value}:" in line and f"component {which} is not a finite number" in line, line


def test_vector_option_refused_with_a_real_mesh_writes_nothing(beam, tmp_path):
    line = expect_one_line_error(["-mesh", beam, "-load_group", "tip", "-modal_nev", "0", "-load_direction", "0,1"], tmp_path)
    assert "-load_direction 0,1: 2 components given, 3 expected" in line


def test_vector_option_help_shows_the_whole_default():
    proc = run_boltrom(["-help"], check=False)
    assert "-load_direction <0.,0.,-1.>" in proc.stdout and "-preload_axis <0.,0.,1.>" in proc.stdout
