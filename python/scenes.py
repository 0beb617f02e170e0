"""The scenes that open part of the joint (paper-step otherwise: step load at t > 0, probe u_z at
the load point), shared by scripts/rom-opening and scripts/bench-contact --scene; and the
frictional scenes of the ROM under Coulomb friction (bench-contact --scene). The third field
says whether the ROM's opening shapes were tuned looking at the scene: yes (their scale and
Krylov vectors), sign (only their taking the load's minus side too) or no."""

SCENES = [  # (name, options, whether the opening shapes' defaults were chosen looking at it)
    ("P5k-F100", ["-preload_force", "5000", "-load_force", "100"], "yes"),
    ("P10k-F300", ["-preload_force", "10000", "-load_force", "300"], "yes"),
    ("P20k-F1k", ["-preload_force", "20000", "-load_force", "1000"], "yes"),
    ("P20k-C1k", ["-preload_force", "20000", "-load_force", "1000", "-load_group", "corner_point"], "yes"),
    ("P2k-C300x", ["-preload_force", "2000", "-load_force", "300", "-load_group", "corner_point", "-load_direction", "1,0,0",
                   "-probe_component", "0"], "no"),
    ("P5k-F300y", ["-preload_force", "5000", "-load_force", "300", "-load_direction", "0,1,0", "-probe_component", "1"], "sign"),
    ("P20k-S1k", ["-preload_force", "20000", "-load_force", "1000", "-load_history", "sine", "-load_frequency", "200"], "sign"),
    ("P2k-F300", ["-preload_force", "2000", "-load_force", "300"], "no"),
    ("P5k-C300", ["-preload_force", "5000", "-load_force", "300", "-load_group", "corner_point"], "no"),
]

# Coulomb friction, mu 0.1 on every pair, level 0.5's figures in docs/results.md "The joint under friction";
# tuned: the slip shapes were added looking at the first scene
FRICTION = ["-contact_law", "coulomb", "-contact_friction", "0.1"]
FRICTION_SCENES = [
    ("mu0.1-P5k-F300", FRICTION + ["-preload_force", "5000", "-load_force", "300", "-ts_end", "0.02"], "yes"),
    ("mu0.1-P20k-F300", FRICTION + ["-preload_force", "20000", "-load_force", "300", "-ts_end", "0.02"], "no"),
    ("mu0.1-P5k-S100x", FRICTION + ["-preload_force", "5000", "-load_force", "100", "-load_direction", "1,0,0",
                                    "-probe_component", "0", "-load_history", "sine", "-load_frequency", "50",
                                    "-ts_end", "0.04"], "no"),
]

# The reduced contact's frictional acceptance (scripts/rom-friction): micro-slip along x, y and z at
# the load point and the corner point, preloads 5 - 20 kN, mu 0.1 - 0.3, 10 - 120 N; a sine of
# FRICTION_FREQUENCY over FRICTION_CYCLES cycles. None of them chose a default of the ROM.
FRICTION_FREQUENCY = 80
FRICTION_CYCLES = 4
_ALONG_X, _ALONG_Y, _ALONG_Z = (["-load_direction", d, "-probe_component", c] for d, c in (("1,0,0", "0"), ("0,1,0", "1"), ("0,0,-1", "2")))
_AT_CORNER = ["-load_group", "corner_point"]


def _frictional(mu, preload, force):
    return ["-contact_friction", str(mu), "-preload_force", str(preload), "-load_force", str(force)]


FRICTION_ACCEPTANCE = [
    ("mu0.15-P10k-X40", _frictional(0.15, 10000, 40) + _ALONG_X),
    ("mu0.15-P10k-X120", _frictional(0.15, 10000, 120) + _ALONG_X),
    ("mu0.1-P5k-Y30", _frictional(0.1, 5000, 30) + _ALONG_Y),
    ("mu0.3-P20k-Z20", _frictional(0.3, 20000, 20) + _ALONG_Z),
    ("mu0.1-P20k-Z50", _frictional(0.1, 20000, 50) + _ALONG_Z),
    ("mu0.2-P5k-CX50", _frictional(0.2, 5000, 50) + _ALONG_X + _AT_CORNER),
    ("mu0.1-P10k-CZ10", _frictional(0.1, 10000, 10) + _ALONG_Z + _AT_CORNER),
    ("mu0.3-P20k-CY100", _frictional(0.3, 20000, 100) + _ALONG_Y + _AT_CORNER),
]
