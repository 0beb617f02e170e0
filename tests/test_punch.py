"""The strict contact law on an eccentric flat punch, against the no-tension foundation's closed
form (the middle-third rule): a known contact length and a known pressure line.

The case (scripts/mesh-joint --kind punch): a steel punch, b = 40 mm wide (x), d = 4 mm deep (y),
20 mm high, on a layer of the same footprint, t = 1 mm thick, E = 2.1 MPa (1e-5 of the punch's),
clamped at its bottom; nu = 0 in both; nodal contact between them. P = 1 N pushes down on a
strip of the punch's top centred at x = e (x = 0 is the middle of the face).

Reference. With nu = 0 a layer whose top follows a rigid punch is a Winkler foundation of
modulus E/t per unit area: a top displacement linear in x is an exact solution of the layer
(u_z = w(x) z/t, u_x = -w'(x) z^2/(2t): no shear, no sigma_xx, so the free sides hold and the
punch's bottom, which moves uniformly in x, sticks to it), and the pressure is linear in x.
Statics then gives, for a foundation that takes no tension:
  e <= b/6: all of the face closed, p = P/(b d) (1 + 12 e x / b^2);
  e > b/6: a contact length c = 3 (b/2 - e) from the compressed edge x = b/2,
           p = 2P/(c d) (x - x0)/c on x > x0 = b/2 - c, the rest open.
Only the opening edge disturbs this, over about t, where the pressed layer meets the unloaded.

How far the model is from that reference, measured once by hand: the zero of a line fitted to
the interior nodal tractions against the reference's, and the largest deviation of those
tractions from the reference line, over its peak (offsets in h = 1 mm on every row):
  e = 7.5 mm, this mesh (h = 1 mm, 2 elements through the layer)   -0.0020 h   2.0e-4
  e = 12.5 mm, this mesh                                           -0.0034 h   3.1e-4
  e = 15.5 mm, this mesh                                           -0.0051 h   5.6e-4
  e = 12.5 mm, level 2 (h = 0.5 mm, 4 elements through the layer) +0.0046 h   1.8e-4
  e = 15.5 mm, level 2                                             +0.0080 h   4.8e-4
  e = 12.5 mm, t = 0.5 mm                                          -0.0039 h   2.0e-4
  e = 12.5 mm, the layer 10 times softer                           -0.0034 h   3.0e-4
  e = 6.5 mm (all closed), this mesh                               +0.013 h    7.2e-5
The deviation grows like t/c (the opening edge's disturbance spans about t) and hardly with h.
The tolerances, 0.05 h and 2e-3 of the peak, are 3.5 - 6 times the largest of these; the nodal
contact set's own resolution is one element.
"""
import h5py
import numpy as np
import pytest

from conftest import make_mesh, run_summary
from test_strict import assert_one_sided

P = 1.0
SCENE = ["-fom", "-static", "false", "-modal_nev", "0", "-contact_law", "strict",
         "-load_group", "load_strip", "-probe_group", "top", "-load_force", str(P), "-static_contact_load",
         "-preload_force", "0", "-ts_dt", "1e-4", "-ts_end", "1e-4",
         "-materials", "layer", "-material_layer_E", "2.1e6", "-material_layer_nu", "0",
         "-material_layer_rho", "1000", "-material_steel_nu", "0", "-part_material", "punch:steel,layer:layer",
         "-output_name", "punch"]


def run_punch(meshdir, tmp_path, e, ranks=1):
    """Meshes the punch with its load strip at x = e [m], runs the FOM; returns the mesh facts,
    the summary and the contact lines (contact_lines)."""
    mesh, info = make_mesh("punch", meshdir / f"punch-{e:g}.msh", 1, ["--punch-eccentricity", str(e)])
    s = run_summary(["-mesh", mesh, "-output_dir", tmp_path] + SCENE, tmp_path, ranks=ranks)
    return info, s, contact_lines(tmp_path / "punch.h5", info["layer_thickness"])


def contact_lines(h5path, t):
    """The contact's node pairs gathered by line across the depth (x): x of each line, the
    normal force on its punch nodes (> 0 in compression), the largest and smallest opening
    (punch over layer) of its pairs, and the largest tangential force on them."""
    with h5py.File(h5path, "r") as f:
        X = f["/geometry/vertices"][...]
        u = f["/vertex_fields/fom_final_displacement"][...]
        F = f["/vertex_fields/fom_final_contact_force"][...]
        part = f["/vertex_fields/part"][...]
    punch = part == part[np.argmax(X[:, 2])]
    on = np.abs(X[:, 2] - t) < 1e-9
    a, b = np.where(on & punch)[0], np.where(on & ~punch)[0]
    a, b = a[np.lexsort((X[a, 1], X[a, 0]))], b[np.lexsort((X[b, 1], X[b, 0]))]
    assert len(a) == len(b) and np.abs(X[a] - X[b]).max() < 1e-12
    x, line = np.unique(X[a, 0], return_inverse=True)
    gap = u[a, 2] - u[b, 2]
    fz = np.bincount(line, F[a, 2])
    gmax = np.array([gap[line == i].max() for i in range(len(x))])
    gmin = np.array([gap[line == i].min() for i in range(len(x))])
    ft = np.array([np.hypot(F[a, 0], F[a, 1])[line == i].max() for i in range(len(x))])
    # the contact forces are equal and opposite on the two sides
    assert np.abs(F[a] + F[b]).max() <= 1e-12 * P
    return dict(x=x, fz=fz, gmax=gmax, gmin=gmin, ft=ft)


def tractions(info, lines):
    """Nodal traction of each line: its force over its tributary area (half at the two edges)."""
    h = info["width"] / info["elements"][0]
    area = np.full(len(lines["x"]), h * info["depth"])
    area[[0, -1]] /= 2
    return lines["fz"] / area, h


def assert_statics(info, s, lines, e, h):
    """The contact forces hold the punch: their sum is P and their resultant acts at x = e (the
    loop's gap tolerance times the layer's stiffness is their only error)."""
    fz, x = lines["fz"], lines["x"]
    assert abs(fz.sum() / P - 1) < 1e-6
    assert abs(-s["preload"]["normal_force_per_pair"]["punch_layer"] / P - 1) < 1e-6
    assert abs((fz * x).sum() / fz.sum() - e) < 1e-6 * h


@pytest.mark.parametrize("e_mm,ranks", [(7.5, 1), (12.5, 1), (12.5, 2), (15.5, 1)])
def test_eccentric_punch_opens_the_far_edge(meshdir, tmp_path, e_mm, ranks):
    """e > b/6: the pairs are closed on one run from the compressed edge, of length
    c = 3 (b/2 - e) within h/2 (the e's put its end x0 half-way between node lines, where the
    reference's traction is 1 - 4 % of its peak: one line too many or too few fails); the
    interior tractions lie on the reference line to 2e-3 of its peak and their fitted zero is
    x0 within 0.05 h; the contact forces are in equilibrium with P; open pairs carry nothing."""
    e = e_mm * 1e-3
    info, s, lines = run_punch(meshdir, tmp_path, e, ranks)
    b, d = info["width"], info["depth"]
    c = 3 * (b / 2 - e)
    x0 = b / 2 - c
    p, h = tractions(info, lines)
    x, tol = lines["x"], s["contact_gap_tolerance"]
    assert_one_sided(s["fom"])
    closed = lines["gmax"] <= tol
    # every pair of a line in the same state; closed lines pressed, open ones open and unloaded
    assert np.all(closed == (lines["gmin"] <= tol))
    assert np.all(lines["gmin"][closed] >= -tol) and p[closed].min() > 0
    assert np.all(lines["gmin"][~closed] > tol) and np.all(lines["fz"][~closed] == 0)
    assert np.all(lines["ft"][~closed] == 0)
    # one run of closed lines from the compressed edge, ending where the reference's does
    first = np.argmax(closed)
    assert closed[first:].all() and not closed[:first].any() and first > 0
    assert abs((b / 2 - (x[first] + x[first - 1]) / 2) - c) <= h / 2
    assert s["fom"]["active_points"] < s["fom"]["contact_points"]
    # the pressure line, on the lines off both ends of the contact (the ends' nodal forces are
    # those of their elements, which the end cuts or the edge bounds)
    inner = np.arange(first + 1, len(x) - 1)
    p_ref = 2 * P / (c * d) * (x - x0) / c
    assert np.abs(p - p_ref)[inner].max() <= 2e-3 * p_ref.max()
    slope, icpt = np.polyfit(x[inner], p[inner], 1)
    assert abs(-icpt / slope - x0) <= 0.05 * h
    assert_statics(info, s, lines, e, h)


def test_punch_inside_the_middle_third_stays_closed(meshdir, tmp_path):
    """e = 6.5 mm < b/6 (6e/b = 0.975): every pair stays closed, the least pressed edge at 2.5 %
    of the mean pressure; the interior tractions lie on P/(b d) (1 + 12 e x / b^2) to 2e-3 of its
    peak (its zero, outside the face, at -b^2/(12 e), fitted within 0.05 h)."""
    e = 6.5e-3
    info, s, lines = run_punch(meshdir, tmp_path, e)
    b, d = info["width"], info["depth"]
    p, h = tractions(info, lines)
    x = lines["x"]
    assert_one_sided(s["fom"])
    assert s["fom"]["active_points"] == s["fom"]["contact_points"]
    assert np.abs(lines["gmax"]).max() <= s["contact_gap_tolerance"] and p.min() > 0
    inner = np.arange(1, len(x) - 1)
    p_ref = P / (b * d) * (1 + 12 * e * x / b**2)
    assert np.abs(p - p_ref)[inner].max() <= 2e-3 * p_ref.max()
    slope, icpt = np.polyfit(x[inner], p[inner], 1)
    assert abs(-icpt / slope + b**2 / (12 * e)) <= 0.05 * h
    assert_statics(info, s, lines, e, h)
