"""Bad input that used to run on, or crash: non-finite option values, meshes missing a preload
layer or one side of a contact pair or with an inverted hexahedron, and ROM files and checkpoints
cut short or with flipped bytes. Each gives one line naming the problem and the fix, a non-zero
exit, and writes nothing (the damaged file itself is left as it was).

Run: /usr/bin/python3 -m pytest -q tests/test_bad_input.py"""
import json
import re
import shutil
import sys

import h5py
import pytest

from conftest import ROOT, run_boltrom, run_summary

sys.path.insert(0, str(ROOT / "python"))
import boltrom_mesh as bm  # noqa: E402

SCENE = ["-options_file", ROOT / "inputs" / "paper-step.yaml", "-rom_n_ccm", "20", "-rom_n_jim", "20",
         "-ts_dt", "1e-4", "-contact_tol_lambda", "1e-9", "-contact_max_inner", "2000"]


def one_line_error(args, tmp_path, ranks=1):
    """Runs args into tmp_path/out; returns (the error line, stdout), checking that it is one line,
    the exit non-zero and nothing written (the summary's folder is made before any computation)."""
    out = tmp_path / "out"
    p = run_boltrom(list(args) + ["-output_dir", out, "-summary", out / "summary.json"], ranks=ranks, check=False)
    lines = [l for l in p.stderr.splitlines() if l.strip()]
    assert p.returncode != 0, p.stdout
    assert len(lines) == 1 and lines[0].startswith("boltrom: error: "), p.stderr
    assert not out.exists() or not any(out.rglob("*")), list(out.rglob("*"))
    return lines[0], p.stdout


# --------------------------------------------------------------------- options that are not finite
@pytest.mark.parametrize("option,value", [
    ("-load_force", "nan"), ("-ts_end", "inf"), ("-ts_dt", "1e999"), ("-contact_tol_lambda", "-Infinity"),
    ("-rayleigh_alpha", "NaN"), ("-preload_force", "+INF")])
def test_non_finite_real_option(joint_small, tmp_path, option, value):
    """Every real option, whoever reads it: refused before the mesh is read (no output at all)."""
    line, out = one_line_error(SCENE + ["-mesh", joint_small[0], option, value], tmp_path)
    assert line == f"boltrom: error: {option} {value}: not a finite number; give a finite real value"
    assert out == ""


def test_non_finite_value_in_a_scene_file(joint_small, tmp_path):
    scene = tmp_path / "scene.yaml"
    scene.write_text(f"mesh: {joint_small[0]}\nts_end: inf\n")
    line, out = one_line_error(["-options_file", ROOT / "inputs" / "paper-step.yaml", "-options_file", scene], tmp_path)
    assert "-ts_end inf: not a finite number" in line and out == ""


def test_non_finite_component_of_a_list(joint_small, tmp_path):
    line, _ = one_line_error(SCENE + ["-mesh", joint_small[0], "-preload_axis", "0, 0, nan"], tmp_path)
    assert "-preload_axis 0, 0, nan: component 3 is not a finite number" in line


# --------------------------------------------------------------------------------- faulty meshes
@pytest.fixture(scope="module")
def faulty(tmp_path_factory):
    """The coarse joint with one fault each, written by boltrom_mesh as the mesh script does."""
    d = tmp_path_factory.mktemp("faulty")

    def write(name, change):
        m = bm.build_joint(0.5)
        change(m)
        bm.write_msh(m, str(d / f"{name}.msh"))
        return d / f"{name}.msh"

    def invert(m):  # top and bottom faces swapped: a mirror image, inside out
        m.parts["plate1"][7] = m.parts["plate1"][7][[4, 5, 6, 7, 0, 1, 2, 3]]

    return {
        "no_preload": write("no_preload", lambda m: [m.surfaces.pop(k) for k in ("preload_lower", "preload_upper")]),
        "half_preload": write("half_preload", lambda m: m.surfaces.pop("preload_upper")),
        "side_a_only": write("side_a_only", lambda m: m.surfaces.pop("contact_washer_nut_b")),
        "side_b_only": write("side_b_only", lambda m: m.surfaces.pop("contact_head_washer_a")),
        "inverted": write("inverted", invert),
    }


def test_mesh_without_preload_layers(faulty, tmp_path):
    """The scene asks for 20 kN of preload; the mesh has no layers to put it on (it ran without
    any preload, silently). With -preload_force 0 the same mesh is accepted."""
    line, _ = one_line_error(SCENE + ["-mesh", faulty["no_preload"]], tmp_path)
    assert f"-preload_force 20000. needs the preload layers 'preload_lower' and 'preload_upper', which mesh {faulty['no_preload']} does not have" in line
    assert "-preload_lower_group" in line and "-preload_force 0" in line
    p = run_boltrom(SCENE + ["-mesh", faulty["no_preload"], "-preload_force", "0", "-fom", "false", "-rom", "false",
                             "-static", "false", "-modal_nev", "0", "-output", "false"])
    assert "preload (no preload layers in mesh) 0. N" in p.stdout


def test_mesh_with_one_preload_layer(faulty, tmp_path):
    line, _ = one_line_error(SCENE + ["-mesh", faulty["half_preload"]], tmp_path)
    assert line.endswith(f"Mesh {faulty['half_preload']} has the preload layer 'preload_lower' but not 'preload_upper': "
                         "add the missing physical group, or name the layers with -preload_lower_group and -preload_upper_group")


@pytest.mark.parametrize("case,words", [
    ("side_a_only", "Contact pair washer_nut has side a (contact_washer_nut_a) but no side b: add the physical surface group contact_washer_nut_b"),
    ("side_b_only", "Contact pair head_washer has side b (contact_head_washer_b) but no side a: add the physical surface group contact_head_washer_a")])
def test_contact_pair_meshed_on_one_side(faulty, tmp_path, case, words):
    """Side b alone used to drop its pair without a word (the run then failed in the contact loop)."""
    line, _ = one_line_error(SCENE + ["-mesh", faulty[case]], tmp_path, ranks=1)
    assert line == "boltrom: error: " + words


def test_inverted_hexahedron_read_from_a_file(faulty, tmp_path):
    line, _ = one_line_error(SCENE + ["-mesh", faulty["inverted"]], tmp_path)
    assert f"Mesh {faulty['inverted']}: the hexahedron at" in line and "in part plate1 is inverted or degenerate" in line
    assert "fix its node order" in line


# ------------------------------------------------------------------ damaged ROM files, checkpoints
@pytest.fixture(scope="module")
def files(joint_small, tmp_path_factory):
    """A ROM file (built by a ROM-only run) and a FOM checkpoint at step 5."""
    d = tmp_path_factory.mktemp("files")
    run_boltrom(SCENE + ["-mesh", joint_small[0], "-fom", "false", "-ts_end", "1e-4", "-rom_file", d / "rom.h5",
                         "-output", "false"])
    run_boltrom(SCENE + ["-mesh", joint_small[0], "-rom", "false", "-ts_end", "5e-4", "-checkpoint_every", "5",
                         "-checkpoint_file", d / "ck", "-output", "false"])
    return joint_small[0], d


def damage(src, dst, how, dataset):
    """A copy of src cut to half its length, or with 8 bytes of one dataset's data overwritten
    (HDF5 keeps no checksum of its data: such a file opens and reads)."""
    data = bytearray(src.read_bytes())
    if how == "truncated":
        data = data[:len(data) // 2]
    else:
        with h5py.File(src) as f:
            off = f[dataset].id.get_chunk_info(0).byte_offset
        data[off + 800:off + 808] = b"\x12" * 8
        with h5py.File(src) as f:  # still a readable file, with other numbers
            assert f[dataset].shape
    dst.write_bytes(bytes(data))
    return bytes(data)


@pytest.mark.parametrize("how", ["truncated", "flipped"])
def test_damaged_rom_file(files, tmp_path, how):
    """Refused before the FOM runs, unless -rom_rebuild names a file: then the ROM is built into it
    (the damaged file left as it is, the new one read by the next run)."""
    mesh, d = files
    bad = tmp_path / "rom.h5"
    data = damage(d / "rom.h5", bad, how, "rom/Kr")
    args = SCENE + ["-mesh", mesh, "-ts_end", "2e-4", "-rom_file", bad]
    line, out = one_line_error(args, tmp_path)
    assert line == (f"boltrom: error: ROM file {bad} is damaged or cut short (it cannot be read through, or its data "
                    "do not match the checksum written with it): build a new one with -rom_rebuild FILE (the same name "
                    "overwrites it), or remove it")
    assert "FOM" not in out and bad.read_bytes() == data
    new = tmp_path / "new.rom.h5"
    p = run_boltrom(args + ["-fom", "false", "-rom_rebuild", new, "-output", "false"])
    assert f"ROM file {bad} is damaged or cut short: building the ROM into {new}, as asked (-rom_rebuild)" in p.stdout
    assert bad.read_bytes() == data and new.exists()
    p = run_boltrom(SCENE + ["-mesh", mesh, "-ts_end", "2e-4", "-rom_file", new, "-fom", "false", "-output", "false"])
    assert f"ROM: reusing {new}" in p.stdout


@pytest.mark.parametrize("how", ["truncated", "flipped"])
def test_damaged_checkpoint(files, tmp_path, how):
    mesh, d = files
    data = damage(d / "ck-fom.ckpt.h5", tmp_path / "ck-fom.ckpt.h5", how, "checkpoint/q")
    line, _ = one_line_error(SCENE + ["-mesh", mesh, "-rom", "false", "-ts_end", "1e-3", "-restart",
                                      "-checkpoint_file", tmp_path / "ck"], tmp_path)
    assert line == (f"boltrom: error: -restart: the checkpoint {tmp_path / 'ck-fom.ckpt.h5'} is damaged or cut short "
                    "(it cannot be read through, or its data do not match the checksum written with it): remove it and "
                    "run again from the start (or from a copy of an intact checkpoint)")
    assert (tmp_path / "ck-fom.ckpt.h5").read_bytes() == data
    # the intact one restarts
    shutil.copy(d / "ck-fom.ckpt.h5", tmp_path / "ok-fom.ckpt.h5")
    p = run_boltrom(SCENE + ["-mesh", mesh, "-rom", "false", "-ts_end", "6e-4", "-restart", "-checkpoint_file",
                             tmp_path / "ok", "-output", "false"])
    assert f"restarted from {tmp_path / 'ok-fom.ckpt.h5'} at step 5" in p.stdout


# ------------------------------------------------------------- a ROM file built for another scene
def test_rom_file_of_another_friction_is_kept_and_refused(joint_small, tmp_path):
    """A ROM file built at mu 0.1: a run at mu 0.2, with another stick stiffness or slip tolerance
    is refused before any model runs, naming the first difference, and the file stays byte for byte (a
    trained ROM was once replaced that way by one built without its training); -rom_rebuild FILE
    builds the ROM for the new scene into FILE, which the next run reuses."""
    rom = tmp_path / "mu0.1.rom.h5"
    args = SCENE + ["-mesh", joint_small[0], "-fom", "false", "-ts_end", "2e-4", "-contact_law", "coulomb",
                    "-preload_force", "5000", "-rom_file", rom]
    run_boltrom(args + ["-contact_friction", "0.1", "-output", "false"])
    kept = rom.read_bytes()
    for change, first in ((["-contact_friction", "0.2"], "pair_head_washer_friction: the file has 0.1, the scene 0.2"),
                          (["-contact_friction", "0.1", "-contact_stick_stiffness_factor", "400"],
                           "pair_head_washer_stick_stiffness: the file has 4.2e+13, the scene 8.4e+13"),
                          (["-contact_friction", "0.1", "-contact_slip_angle_tolerance", "0.05"],
                           "contact_slip_angle_tolerance: the file has 0.01, the scene 0.05")):
        line, out = one_line_error(args + change, tmp_path)
        assert line == (f"boltrom: error: ROM file {rom} was built for another scene ({first}) and is kept as it is: "
                        "point -rom_file at a new file, or build one for this scene with -rom_rebuild FILE (the same "
                        "name overwrites it)"), line
        assert "ROM:" not in out and rom.read_bytes() == kept
    line, _ = one_line_error(args + ["-contact_friction", "0.2", "-rom_rebuild", "true"], tmp_path)
    assert "-rom_rebuild takes the file to build the ROM into (got 'true')" in line
    new = tmp_path / "mu0.2.rom.h5"
    p = run_boltrom(args + ["-contact_friction", "0.2", "-rom_rebuild", new, "-output", "false"])
    assert f"building the ROM into {new}, as asked (-rom_rebuild)" in p.stdout and rom.read_bytes() == kept
    p = run_boltrom([a if a != rom else new for a in args] + ["-contact_friction", "0.2", "-output", "false"])
    assert f"ROM: reusing {new}" in p.stdout


@pytest.mark.parametrize("change,first", [
    (["-load_direction", "1,0,0"], r"input_load: the file has 'load_point' along 0,0,-1, the scene 'load_point' along "
                                   r"1,0,0; -rom_allow_foreign_load projects it with the rows the file keeps"),
    (["-support_group", "corner_point"], r"support: the file has 'none', the scene 'corner_point:yz'"),
    (["-preload_axis", "0,0,-1"], r"preload_axis: the file has '0,0,1', the scene '0,0,-1'"),
    (["-contact_activation_gap", "1e-8"], r"contact_activation_gap: the file has [0-9.]+e-1[0-9], the scene 1e-08"),
    (["-static_contact_load"], r"static_contact_load: the file has 0, the scene 1")])
def test_rom_file_of_another_load_support_or_contact_setting_is_refused(files, tmp_path, change, first):
    """The settings besides materials and friction that the basis, the stored load or the stored
    preloaded state are solved with (once outside the fingerprint: a file built for a load along z
    served a load along x with its z projection): each is refused before any model runs, naming
    the first difference, and the file stays byte for byte."""
    mesh, d = files
    rom = tmp_path / "rom.h5"
    shutil.copy(d / "rom.h5", rom)
    kept = rom.read_bytes()
    line, out = one_line_error(SCENE + ["-mesh", mesh, "-fom", "false", "-ts_end", "1e-4", "-rom_file", rom] + change, tmp_path)
    assert re.fullmatch(f"boltrom: error: ROM file {re.escape(str(rom))} was built for another scene \\({first}\\) and is "
                        r"kept as it is: point -rom_file at a new file, or build one for this scene with -rom_rebuild FILE "
                        r"\(the same name overwrites it\)", line), line
    assert "ROM:" not in out and rom.read_bytes() == kept


def test_rom_file_serves_another_direction_only_when_asked(files, tmp_path):
    """With -rom_allow_foreign_load a load along another direction is projected with the rows the
    file keeps at its point: reversed, the ROM's response reverses (the file's own projection, along
    the old direction, would have given the same sign). -rom_rebuild needs a -rom_file to replace."""
    mesh, d = files
    args = SCENE + ["-mesh", mesh, "-fom", "false", "-ts_end", "1e-3", "-rom_file", d / "rom.h5", "-output", "false"]
    kept = (d / "rom.h5").read_bytes()
    own = run_summary(args, tmp_path, name="own")["rom"]
    p = run_boltrom(args + ["-load_direction", "0,0,1", "-rom_allow_foreign_load", "-summary", tmp_path / "up.json"])
    up = json.loads((tmp_path / "up.json").read_text())["rom"]
    assert "ROM: the load at 'load_point' along 0,0,1 is not the input of" in p.stdout
    assert own["source"] == up["source"] == "file" and (d / "rom.h5").read_bytes() == kept
    print("probe at the end, the file's direction and reversed:", own["probe_final"], up["probe_final"])
    assert own["probe_final"] < 0 < up["probe_final"] and up["probe_final"] == pytest.approx(-own["probe_final"], rel=0.2)
    line, _ = one_line_error(SCENE + ["-mesh", mesh, "-rom_file", "", "-rom_rebuild", tmp_path / "new.h5"], tmp_path)
    assert line == (f"boltrom: error: -rom_rebuild {tmp_path / 'new.h5'} replaces a -rom_file that does not match the "
                    f"scene, but -rom_file is empty: give -rom_file {tmp_path / 'new.h5'} to build the ROM into that file")
