"""CalculiX references for boltrom's transient under contact and for a load cycle with friction
(scripts/ccx-crosscheck --only dynamic, --only hysteresis; docs/verification.md section 10).

Transient. ccx 2.20's implicit *DYNAMIC with penalty contact pairs does not run these problems:
its energy rules for contact ask for ever smaller increments (with DIRECT it stops at the second
increment; without, it cuts back to 1e-8 s and stops). The reference therefore models each of
boltrom's node pairs as the strict law treats a closed pair: a GAPUNI element along the pair's
normal (+z on every pair here: one-sided, a penalty spring when closed) and the pair's two
tangential components tied by *EQUATION (a closed pair sticks). Elements C3D8 against boltrom's
-element full (ccx's C3D8I is another incompatible-modes formulation than boltrom's); no damping
in either code; ccx *DYNAMIC, DIRECT, ALPHA=0 (the alpha method without numerical damping is the
trapezoidal rule, boltrom's Newmark beta 1/4, gamma 1/2) with boltrom's time step; the load off
at t = 0 and on from t = dt, as boltrom's step load.

Load cycle. A load taken from 0 to +F, to -F and back to +F with Coulomb friction (ccx's
surface-to-surface penalty contact with *FRICTION, the same elastic stick as boltrom's):
ccx *STATIC, DIRECT through an *AMPLITUDE of the load factors, boltrom -ts_quasistatic with a
sine load sampled at the same increments. Two cases: two pressed blocks, the upper one a shear
spring beside the interface's friction (its top face held in x and y), so that the interface
slides as a whole both ways and the loop stays bounded; ccx finishes it in every run with a
normal penalty of 1e6 E/m, and the two codes agree to a few 1e-3. And the joint's axial load
(the friction comparison of scripts/ccx-crosscheck, the load point held in y and z), where the
two codes' loops differ by about 60 % (reported).

ccx reads at most 20 characters of a number: the amplitude's factors are written by ccx_number
(sin(2 pi) printed to 15 digits was read as -0.2449, a jump of a quarter of the load at the
cycle's second zero crossing).
"""
import importlib.machinery
import importlib.util
import os
import subprocess
import sys
import time
from pathlib import Path

import h5py
import numpy as np

ROOT = Path(__file__).resolve().parents[1]


def _crosscheck():
    """scripts/ccx-crosscheck as a module (its mesh reader, ccx runner and .dat parsers)."""
    name = "ccx_crosscheck"
    if name in sys.modules:
        return sys.modules[name]
    loader = importlib.machinery.SourceFileLoader(name, str(ROOT / "scripts" / "ccx-crosscheck"))
    spec = importlib.util.spec_from_loader(name, loader)
    mod = importlib.util.module_from_spec(spec)
    sys.modules[name] = mod
    loader.exec_module(mod)
    return mod


cc = _crosscheck()
E_STEEL, NU_STEEL, RHO_STEEL = cc.MATERIALS["steel"]
cc.PART_MATERIAL.setdefault("upper", "steel")
cc.PART_MATERIAL.setdefault("lower", "steel")
PAIR = "upper_lower"


def face_weights(mesh, group):
    """Node -> share of a unit force spread over a face group by area (each face's area in
    quarters to its corners), as boltrom spreads a load over a surface group."""
    w = {}
    for q in mesh.surfaces[group]:
        X = mesh.xyz(q)
        area = 0.5 * np.linalg.norm(np.cross(X[2] - X[0], X[3] - X[1]))
        for t in q:
            w[int(t)] = w.get(int(t), 0.0) + area / 4
    tot = sum(w.values())
    return {t: v / tot for t, v in w.items()}


def blocks_model(mesh, eltype="C3D8"):
    """The two blocks' lines: nodes, elements, steel, the clamp and the node set TOP (the upper
    block's top face)."""
    out = ["*HEADING", "two pressed blocks exported by scripts/ccx_dynamic.py", "*NODE"]
    for t in mesh.tags:
        x, y, z = np.where(np.abs(mesh.coords[t - 1]) < 1e-15, 0.0, mesh.coords[t - 1])
        out.append(f"{t}, {x:.15g}, {y:.15g}, {z:.15g}")
    ids = mesh.element_ids()
    for name, H in mesh.parts.items():
        out.append(f"*ELEMENT, TYPE={eltype}, ELSET={name}")
        out.extend(f"{e}, " + ", ".join(str(int(v)) for v in h) for e, h in zip(ids[name], H))
    out += ["*MATERIAL, NAME=steel", "*ELASTIC", f"{E_STEEL:.15g}, {NU_STEEL:.15g}", "*DENSITY", f"{RHO_STEEL:.15g}"]
    out += [f"*SOLID SECTION, ELSET={name}, MATERIAL=steel" for name in mesh.parts]
    out += ["*NSET, NSET=CLAMP", cc._lines(np.unique(mesh.surfaces["clamp"])), "*BOUNDARY", "CLAMP, 1, 3"]
    out += ["*NSET, NSET=TOP", cc._lines(np.unique(mesh.surfaces["top"]))]
    return out


def deck_blocks(mesh, k, steps_text, eltype="C3D8"):
    """The two blocks (blocks_model) with node-pair contact on upper_lower (gap_lines, penalty
    k [N/m]), then `steps_text`."""
    return "\n".join(blocks_model(mesh, eltype) + gap_lines(mesh, [PAIR], k)) + "\n" + steps_text


def load_lines(mesh, force, direction):
    """*CLOAD lines: `force` [N] along axis `direction` (1..3) over the top face by area."""
    w = face_weights(mesh, "top")
    return "".join(f"{t}, {direction}, {force * v:.15g}\n" for t, v in sorted(w.items()))


def gap_lines(mesh, pairs, k, first_id=None, untied=()):
    """Node-pair contact: a GAPUNI element along +z from each side-b node to its side-a partner
    (one-sided, penalty k [N/m] when closed) and the two tangential components tied by *EQUATION
    (stick), except at the side-b nodes in `untied`."""
    e = first_id or sum(len(h) for h in mesh.parts.values()) + 1
    out = ["*ELEMENT, TYPE=GAPUNI, ELSET=GAPS"]
    eq = ["*EQUATION"]
    for pair in pairs:
        a, b = mesh.pair_nodes(pair)
        z = mesh.xyz(b)[:, 2]
        if np.ptp(z) > 1e-12:
            raise SystemExit(f"ccx_dynamic: pair {pair} is not in a plane z = const; its gap elements act along z")
        for i, j in zip(b, a):
            out.append(f"{e}, {int(i)}, {int(j)}")
            e += 1
            for d in (1, 2) if int(i) not in untied else ():
                eq += ["2", f"{int(j)}, {d}, 1., {int(i)}, {d}, -1."]
    out += ["*GAP, ELSET=GAPS", f"0., 0., 0., 1., , {k:.6g}"]
    return out + eq


def deck_joint_dynamic(mesh, preload_node_force, k, dt, steps, load):
    """The joint with node-pair contact (gap_lines, penalty k [N/m]): step 1 the preload
    (static), step 2 the load [N down at the load point] as a step, `steps` increments of dt."""
    s = cc.deck_model(mesh, "C3D8", None)
    s += "\n".join(gap_lines(mesh, cc.PAIRS, k)) + "\n"
    lower = np.unique(mesh.surfaces["preload_lower"])
    upper = np.unique(mesh.surfaces["preload_upper"])
    s += "*NSET, NSET=PRELOW\n" + cc._lines(lower) + "\n*NSET, NSET=PREUP\n" + cc._lines(upper) + "\n"
    s += f"*AMPLITUDE, NAME=ON\n0., 0., {dt:.15g}, 1., {10 * steps * dt:.15g}, 1.\n"
    # ccx asks for energy output in the first step of a nonlinear dynamic analysis
    s += (f"*STEP, INC=1000\n*STATIC\n1.0, 1.0\n*CLOAD\nPRELOW, 3, {preload_node_force:.15g}\n"
          f"PREUP, 3, {-preload_node_force:.15g}\n*NODE PRINT, NSET=LOADPT\nU\n*EL FILE\nENER\n*END STEP\n")
    s += (f"*STEP, INC={steps + 10}\n*DYNAMIC, DIRECT, ALPHA=0\n{dt:.15g}, {steps * dt:.15g}\n"
          f"*CLOAD, AMPLITUDE=ON\nLOADPT, 3, {-load:.15g}\n*NODE PRINT, NSET=LOADPT\nU\n*END STEP\n")
    return s


def add_arguments(ap):
    g = ap.add_argument_group("dynamic (--only dynamic)")
    g.add_argument("--dynamic-case", choices=["joint", "blocks", "both"], default="both",
                   help="the joint's transient, the two blocks' (closed contact throughout), or both (default)")
    g.add_argument("--dynamic-blocks-load", type=float, default=120.0,
                   help="blocks: the step load along x on the upper block's top face [N] (default 120: under the "
                        "1 kN press every node pair stays closed; from about 130 N the upper block lifts and bounces)")
    g.add_argument("--dynamic-blocks-gap-stiffness", type=float, default=1e14,
                   help="blocks: ccx's GAPUNI stiffness per node pair [N/m] (default 1e14)")
    g.add_argument("--tol-dynamic-blocks", type=float, default=5e-5,
                   help="blocks: largest difference of the top's u_x over the history, over the largest (default 5e-5)")
    g.add_argument("--dynamic-steps", type=int, default=100,
                   help="time steps of the transient after the load's step (default 100)")
    g.add_argument("--dynamic-dt", type=float, default=1e-4, help="time step [s] of both codes (default 1e-4)")
    g.add_argument("--dynamic-gap-stiffness", type=float, default=1e12,
                   help="ccx's GAPUNI stiffness per node pair [N/m] (default 1e12)")
    g.add_argument("--dynamic-laws", default="strict,stick",
                   help="boltrom's contact laws compared with the one ccx run, comma separated (default strict,stick)")
    g.add_argument("--tol-dynamic", type=float, default=5e-2,
                   help="strict law: largest difference of the load point's u_z due to the load over the history, over "
                        "ccx's largest (default 5e-2)")
    g.add_argument("--tol-dynamic-stick", type=float, default=1e-2,
                   help="stick law: the same (default 1e-2)")


BLOCKS_PRESS = 1000.0  # N, the upper block pressed on the lower one through its top face
BLOCKS_DT, BLOCKS_STEPS = 1e-6, 300  # about five periods of the block's first mode (18 kHz)


def run_dynamic_blocks(a, work, res):
    """Two steel blocks (scripts/mesh-joint --kind blocks, level 1), the upper pressed on the lower
    by BLOCKS_PRESS through its top face (boltrom's preload layers clamp and top, as the friction
    tests), then a step load along x on the top face; strict law, no damping; u_x at the top's
    corner node (0, 0, 0.02) compared at every step."""
    msh = work / "blocks-L1.msh"
    if not msh.exists():
        subprocess.run([sys.executable, str(ROOT / "scripts" / "mesh-joint"), "--kind", "blocks", "--level", "1",
                        "--output", str(msh)], check=True, capture_output=True)
    mesh = cc.Mesh(msh)
    top = np.unique(mesh.surfaces["top"])
    probe = int(top[np.argmin(np.linalg.norm(mesh.xyz(top) - [0.0, 0.0, 0.02], axis=1))])
    T, n, dt = a.dynamic_blocks_load, BLOCKS_STEPS, BLOCKS_DT
    args = ["-mesh", msh, "-element", "full", "-fom", "true", "-rom", "false", "-static", "false", "-modal_nev", "0",
            "-contact_law", "strict", "-preload_lower_group", "clamp", "-preload_upper_group", "top",
            "-preload_force", BLOCKS_PRESS, "-preload_axis", "0,0,1", "-load_group", "top", "-load_direction", "1,0,0",
            "-load_force", T, "-load_history", "step", "-probe_group", "top", "-probe_component", 0,
            "-rayleigh_alpha", 0, "-rayleigh_beta", 0, "-ts_dt", dt, "-ts_end", n * dt,
            "-output_dir", work / "b-dynamic-blocks", "-output_name", "fom"]
    sm, bdt, cmd = cc.run_boltrom(args, a.ranks, work / "b-dynamic-blocks.json", work / "b-dynamic-blocks.log")
    with h5py.File(work / "b-dynamic-blocks" / "fom.h5", "r") as f:
        X = np.array(f["/geometry/vertices"])
        U = np.array(f["/vertex_fields/fom_final_displacement"])
        ub = np.array(f["/fom/probe"]).ravel()
    # boltrom probes the first vertex of the group: check that it is this node (its final u_x)
    v = int(np.argmin(np.linalg.norm(X - mesh.xyz([probe])[0], axis=1)))
    if abs(U[v, 0] - ub[-1]) > 1e-12 * max(abs(ub[-1]), 1e-30):
        raise RuntimeError("dynamic blocks: boltrom's probe is not the top's corner node (0, 0, 0.02)")
    fnode = sm["preload"]["force"] * sm["preload"]["layer_force_scale"] / len(top)
    s1 = (f"*STEP, INC=1000\n*STATIC\n1.0, 1.0\n*CLOAD\nTOP, 3, {-fnode:.15g}\n*NODE PRINT, NSET=PROBE\nU\n"
          "*EL FILE\nENER\n*END STEP\n")
    s2 = (f"*AMPLITUDE, NAME=ON\n0., 0., {dt:.15g}, 1., {10 * n * dt:.15g}, 1.\n*STEP, INC={n + 10}\n"
          f"*DYNAMIC, DIRECT, ALPHA=0\n{dt:.15g}, {n * dt:.15g}\n*CLOAD, AMPLITUDE=ON\n" + load_lines(mesh, T, 1)
          + "*NODE PRINT, NSET=PROBE\nU\n*END STEP\n")
    deck = deck_blocks(mesh, a.dynamic_blocks_gap_stiffness, f"*NSET, NSET=PROBE\n{probe}\n" + s1 + s2)
    dat, cdt, _ = cc.run_ccx(work, "dynamic-blocks", deck, a.threads)
    uc = np.array([d[probe][0] for _t, d in cc.dat_displacements(dat)])
    if len(uc) != n + 1 or len(ub) != n + 1:
        raise RuntimeError(f"dynamic blocks: ccx gave {len(uc)} and boltrom {len(ub)} points, expected {n + 1}")
    diff = np.abs(ub - uc)
    scale = np.abs(uc).max()
    r = dict(load=T, press=BLOCKS_PRESS, steps=n, dt=dt, gap_stiffness=a.dynamic_blocks_gap_stiffness,
             points_compared=int(len(uc)), ccx=uc.tolist(), boltrom=ub.tolist(), max_diff=float(diff.max()),
             max_ccx=float(scale), rel=float(diff.max() / scale), worst_step=int(np.argmax(diff)),
             boltrom_active_points_end=int(sm["fom"]["active_points"]), contact_points=sm["fom"]["contact_points"],
             boltrom_reclosed_points=sm["fom"]["reclosed_points"], ccx_seconds=cdt, boltrom_seconds=bdt,
             command=" ".join(str(c) for c in cmd))
    res["dynamic_blocks"] = r
    res["checks"].append(dict(name="dynamic blocks u_x history", ccx=float(scale), boltrom=float(scale + diff.max()),
                              rel=r["rel"], tol=a.tol_dynamic_blocks, ok=r["rel"] <= a.tol_dynamic_blocks))
    print(f"\ntwo blocks, {BLOCKS_PRESS:g} N press, {T:g} N step along x (strict law / GAPUNI {r['gap_stiffness']:.3g} N/m "
          f"per node pair; C3D8 / -element full; dt {dt:g} s, {n} steps): top corner u_x, largest difference "
          f"{r['max_diff']:.3g} m at step {r['worst_step']}, {r['rel']:.2e} of the largest ({scale:.4g} m), over "
          f"{r['points_compared']} points; boltrom's closed points at the end {r['boltrom_active_points_end']}/"
          f"{r['contact_points']}, reclosed {r['boltrom_reclosed_points']}; ccx {cdt:.1f} s, boltrom {bdt:.1f} s")
    return r


def run_dynamic(a, work, msh, mesh, res):
    """ccx's transient and boltrom's (-element full, no damping) under each law of
    --dynamic-laws, the same preload (boltrom's calibrated layer forces, from its first run), load
    and steps; compares the load point's u_z due to the load at every step."""
    n, dt = a.dynamic_steps, a.dynamic_dt
    laws = [w.strip() for w in a.dynamic_laws.split(",") if w.strip()]
    tol = {"strict": a.tol_dynamic, "stick": a.tol_dynamic_stick}
    runs, fnode, uc, cdt = {}, None, None, None
    for law in laws:
        if law not in tol:
            raise SystemExit(f"--dynamic-laws: {law} is not strict or stick")
        args = ["-mesh", msh, "-element", "full", "-fom", "true", "-rom", "false", "-static", "false",
                "-modal_nev", "0", "-contact_law", law, "-rayleigh_alpha", 0, "-rayleigh_beta", 0,
                "-load_force", a.load, "-load_history", "step", "-ts_dt", dt, "-ts_end", n * dt,
                "-output_dir", work / f"b-dynamic-{law}", "-output_name", "fom"]
        sm, bdt, cmd = cc.run_boltrom(args, a.ranks, work / f"b-dynamic-{law}.json", work / f"b-dynamic-{law}.log")
        with h5py.File(work / f"b-dynamic-{law}" / "fom.h5", "r") as f:
            ub = np.array(f["/fom/probe"]).ravel()
            tb = np.array(f["/fom/time"]).ravel()
        if fnode is None:
            nlow = len(np.unique(mesh.surfaces["preload_lower"]))
            fnode = sm["preload"]["force"] * sm["preload"]["layer_force_scale"] / nlow
            deck = deck_joint_dynamic(mesh, fnode, a.dynamic_gap_stiffness, dt, n, a.load)
            dat, cdt, _ = cc.run_ccx(work, "dynamic", deck, a.threads)
            uc = np.array([list(d.values())[0][2] for _t, d in cc.dat_displacements(dat)])  # the preload, then every increment
        if len(uc) != n + 1 or len(ub) != n + 1:
            raise RuntimeError(f"dynamic: ccx gave {len(uc)} and boltrom {len(ub)} points, expected {n + 1}")
        dc, db = uc - uc[0], ub - ub[0]
        diff = np.abs(db - dc)
        scale = np.abs(dc).max()
        r = dict(law=law, points_compared=int(len(dc)), time=tb.tolist(), boltrom=db.tolist(),
                 max_diff=float(diff.max()), rel=float(diff.max() / scale), worst_step=int(np.argmax(diff)),
                 preload_uz=float(ub[0]), boltrom_seconds=bdt, preload_open_points=sm["fom"]["contact_points"] - sm["preload"]["active_points"],
                 reclosed_points=sm["fom"]["reclosed_points"], contact_points=sm["fom"]["contact_points"],
                 layer_force_scale=sm["preload"]["layer_force_scale"], command=" ".join(str(c) for c in cmd))
        runs[law] = r
        res["checks"].append(dict(name=f"dynamic u_z history, {law}", ccx=float(scale), boltrom=float(scale + diff.max()),
                                  rel=r["rel"], tol=tol[law], ok=r["rel"] <= tol[law]))
    out = dict(steps=n, dt=dt, gap_stiffness=a.dynamic_gap_stiffness, ccx=(uc - uc[0]).tolist(),
               ccx_preload_uz=float(uc[0]), max_ccx=float(np.abs(uc - uc[0]).max()), ccx_seconds=cdt, laws=runs)
    res["dynamic"] = out
    print_dynamic(out)
    return out


def print_dynamic(r):
    laws = list(r["laws"])
    print(f"\ntransient of the joint (ccx: GAPUNI {r['gap_stiffness']:.3g} N/m per node pair, tangential ties; "
          f"C3D8 / -element full; no damping; dt {r['dt']:g} s, {r['steps']} steps), the load point's u_z due to the load [um]")
    print(f"preload u_z [um]: ccx {r['ccx_preload_uz'] * 1e6:.4f}, " + ", ".join(
        f"boltrom {w} {r['laws'][w]['preload_uz'] * 1e6:.4f}" for w in laws))
    print(f"{'t [ms]':>8s} {'ccx':>10s} " + " ".join(f"{'boltrom ' + w:>15s}" for w in laws))
    t = r["laws"][laws[0]]["time"]
    for i in range(0, r["steps"] + 1, max(1, r["steps"] // 10)):
        print(f"{t[i] * 1e3:8.2f} {r['ccx'][i] * 1e6:10.3f} " + " ".join(f"{r['laws'][w]['boltrom'][i] * 1e6:15.3f}" for w in laws))
    for w in laws:
        x = r["laws"][w]
        print(f"{w}: largest difference {x['max_diff'] * 1e6:.3f} um at step {x['worst_step']}, {x['rel']:.2e} of ccx's "
              f"largest |u_z| ({r['max_ccx'] * 1e6:.1f} um), over {x['points_compared']} points; open contact points after "
              f"the preload {x['preload_open_points']}/{x['contact_points']}, reclosed {x['reclosed_points']}; boltrom {x['boltrom_seconds']:.1f} s")
    print(f"ccx {r['ccx_seconds']:.1f} s")


# ---------------------------------------------------------------------------
# A load cycle with friction
# ---------------------------------------------------------------------------
def cycle_loads(m):
    """The cycle's load factors at its increments: F sin(2 pi t) at t = k / (4 m), k = 1 .. 5 m
    (up to +F, down to -F, up to +F again), m increments a quarter."""
    k = np.arange(1, 5 * m + 1)
    return np.sin(2 * np.pi * k / (4 * m))


def ccx_number(v):
    """v for a ccx data line: ccx reads at most 20 characters of a number and drops the rest
    without a word, so sin(2 pi) = -2.44929359829471e-16 (21 characters) would be read as
    -0.2449. 12 significant digits, and zero for what is round-off of zero."""
    return "0." if abs(v) < 1e-12 else f"{v:.12g}"


def deck_cycle(mesh, preload_node_force, slope, mu, stick, load, m):
    """The friction deck of scripts/ccx-crosscheck (penalty contact with Coulomb friction, the
    load point held in y and z) with its axial load taken round the cycle: ccx *STATIC, DIRECT in
    5 m equal increments, an *AMPLITUDE through the cycle's load factors (linear between them;
    only its values at the increments enter). ALEA 0 (*CONTROLS, PARAMETERS=CONTACT; the other
    three at their defaults): where its iterations repeat a pattern, ccx 2.20 by default switches
    a random tenth of its contact elements, and the same deck then takes other iterations from one
    run to the next; without, two runs are the same to the bit."""
    n = 5 * m
    s = cc.deck_friction(mesh, "C3D8I", preload_node_force, slope, mu, stick, load, n, "surface", True)
    f = cycle_loads(m)
    amp = "*AMPLITUDE, NAME=CYCLE\n0., 0.\n" + "".join(f"{(k + 1) / n:.15g}, {ccx_number(v)}\n" for k, v in enumerate(f))
    first = s.index("*STEP")
    s = s[:first] + amp + s[first:]
    old = f"*CLOAD\nLOADPT, 1, {load:.15g}\n"
    if s.count(old) != 1:
        raise RuntimeError("deck_cycle: the friction deck's axial load line was not found")
    s = s.replace(old, f"*CLOAD, AMPLITUDE=CYCLE\nLOADPT, 1, {load:.15g}\n")
    static = f"*STATIC, DIRECT\n{1.0 / n:.15g}, 1.0\n"
    if s.count(static) != 1:
        raise RuntimeError("deck_cycle: the friction deck's load step was not found")
    return s.replace(static, static + "*CONTROLS, PARAMETERS=CONTACT\n0.001, 0., 100, 60\n")


def run_ccx_retried(workdir, job, text, max_iterations, attempts):
    """ccx on one thread, stopped when an increment takes more than `max_iterations` Newton
    iterations and started again, up to `attempts` times: with surface-to-surface contact and
    fixed increments ccx 2.20 has no iteration limit (its cap, ITF2F of *CONTROLS, acts only with
    automatic increments), and where its contact elements switch on and off from one iteration to
    the next it iterates without end. A new start helps only where the deck leaves ccx's random
    switching of contact elements on (ALEA of *CONTROLS, 0.1 by default; deck_cycle sets 0).
    Returns the .dat text, the seconds of the last attempt and the number of attempts."""
    path = Path(workdir) / f"{job}.inp"
    path.write_text(text)
    env = dict(os.environ, OMP_NUM_THREADS="1", CCX_NPROC_STIFFNESS="1", CCX_NPROC_EQUATION_SOLVER="1")
    cvg = Path(workdir) / f"{job}.cvg"
    for attempt in range(1, attempts + 1):
        cvg.unlink(missing_ok=True)
        t0 = time.perf_counter()
        with open(Path(workdir) / f"{job}.log", "w") as log:
            proc = subprocess.Popen(["ccx", "-i", job], cwd=workdir, stdout=log, stderr=subprocess.STDOUT, env=env)
            stalled = False
            while proc.poll() is None:
                time.sleep(0.5)
                lines = cvg.read_text().splitlines() if cvg.exists() else []
                last = lines[-1].split() if lines else []
                if len(last) > 3 and last[3].isdigit() and int(last[3]) > max_iterations:
                    proc.kill()
                    proc.wait()
                    stalled = True
        dt = time.perf_counter() - t0
        if stalled:
            print(f"ccx {job}: attempt {attempt} stopped, {max_iterations} iterations in increment {last[1]}")
            continue
        out = (Path(workdir) / f"{job}.log").read_text()
        if proc.returncode != 0 or "ERROR" in out:
            err = [line for line in out.splitlines() if "ERROR" in line][:5]
            raise RuntimeError(f"ccx {job} failed ({proc.returncode}): {err} (see {workdir}/{job}.log)")
        return (Path(workdir) / f"{job}.dat").read_text(), dt, attempt
    raise RuntimeError(f"ccx {job}: no attempt of {attempts} converged (see {workdir}/{job}.cvg)")


def loop_area(force, u):
    """The work of the load round the loop, closed from the first to the last increment at +F:
    the trapezoidal integral of F du, which is the dissipation per cycle in a quasi-static cycle
    (the stored energy is the same at both ends when the state is)."""
    force, u = np.asarray(force), np.asarray(u)
    return float(np.sum(0.5 * (force[1:] + force[:-1]) * np.diff(u)))


def first_at(ratio, loads, start, stop, level):
    """The first increment in [start, stop) at which `ratio` reaches `level`, and its load."""
    for k in range(start, stop):
        if ratio[k] >= level:
            return k, float(loads[k])
    return None, None


def add_cycle_arguments(ap):
    g = ap.add_argument_group("hysteresis (--only hysteresis)")
    g.add_argument("--cycle-case", choices=["blocks", "joint", "both"], default="both",
                   help="two pressed blocks (ccx finishes every run: the comparison held to tolerances), the joint at "
                        "--level (about 5 min of ccx; its loop is reported, see --tol-cycle-area), or both (default)")
    g.add_argument("--cycle-blocks-load", type=float, default=200.0,
                   help="blocks: the cycle's amplitude, N along x on the upper block's bottom face (default 200: twice mu "
                        "times the 1 kN press)")
    g.add_argument("--cycle-blocks-level", type=float, default=2,
                   help="blocks: mesh level (scripts/mesh-joint --kind blocks; default 2: 4 x 4 x 4 elements a block, 25 "
                        "node pairs)")
    g.add_argument("--cycle-blocks-quarter", type=int, default=12,
                   help="blocks: increments per quarter cycle (default 12; the cycle takes 5 quarters)")
    g.add_argument("--cycle-blocks-slope", type=float, default=1e6,
                   help="blocks: ccx's normal contact penalty, x E(steel) per metre (default 1e6, boltrom's penalty under "
                        "the coulomb law: from 1e5 to 1e7 the comparison moves by 1e-3 at most, at 1e8 it differs by 1.3 - 1.9 %%, at "
                        "1e9 ccx's friction misses mu N by 8 %%)")
    g.add_argument("--tol-cycle-blocks-u", type=float, default=5e-3,
                   help="blocks: largest difference of the probe's u_x over the cycle, over ccx's range (default 5e-3)")
    g.add_argument("--tol-cycle-blocks-area", type=float, default=5e-3,
                   help="blocks: relative difference of the loop's area, the dissipation per cycle (default 5e-3)")
    g.add_argument("--tol-cycle-blocks-onset", type=float, default=2.5e-3,
                   help="blocks: difference of the load at which the interface slides as a whole (its friction at "
                        "--macro-slip times mu N), over the amplitude, in each branch (default 2.5e-3)")
    g.add_argument("--tol-cycle-blocks-slip", type=float, default=1e-3,
                   help="blocks: largest |friction / (mu N) - 1| while the interface slides, in each code (default 1e-3)")
    g.add_argument("--cycle-load", type=float, default=2400.0,
                   help="joint: the cycle's amplitude, N along x at the load point (default 2400: beyond the plate interface's "
                        "macro-slip near 2.1 kN, as the friction comparison's end load)")
    g.add_argument("--cycle-quarter", type=int, default=3,
                   help="joint: increments per quarter cycle (default 3; the cycle takes 5 quarters; with 6 ccx iterates "
                        "without end at the second zero crossing)")
    g.add_argument("--cycle-max-iterations", type=int, default=600,
                   help="stop ccx when one increment takes more Newton iterations (default 600; on the joint converging "
                        "increments take 11 - 206, on the blocks at most 20)")
    g.add_argument("--cycle-attempts", type=int, default=1,
                   help="joint: ccx starts at most (default 1: with ALEA 0 its runs are the same to the bit)")
    g.add_argument("--tol-cycle-area", type=float, default=None,
                   help="joint: relative difference of the loop's area; reported, and held only when given (the two codes' "
                        "loops differ by about 60 %% on the level-0.5 joint: docs/verification.md section 10); macro-slip "
                        "(--macro-slip) must start within one increment of each other in every branch")


def run_hysteresis(a, work, msh, mesh, res):
    """The joint's axial load round a cycle with Coulomb friction (mu 0.1 on every pair, elastic
    stick 200 E/m in both codes, the load point held in y and z), quasi-static: boltrom
    -ts_quasistatic with a sine load sampled at the increments, ccx *STATIC, DIRECT through the
    same load factors. Compares u_x due to the load at every increment, the loop's area and the
    increments at which slip starts in each branch."""
    m, F, mu_v = a.cycle_quarter, a.cycle_load, a.friction_mu
    n = 5 * m
    args = ["-mesh", msh, "-element", "incompatible", "-fom", "true", "-rom", "false", "-static", "false",
            "-modal_nev", "0", "-contact_law", "coulomb", "-contact_friction", mu_v,
            "-contact_stick_stiffness_factor", a.friction_stick, "-ts_quasistatic", "-load_history", "sine",
            "-load_frequency", 1.0, "-ts_dt", 1.0 / (4 * m), "-ts_end", n / (4 * m), "-load_direction", "1,0,0",
            "-load_force", F, "-probe_component", 0, "-support_group", "load_point", "-support_components", "1,2",
            "-output_dir", work / "b-cycle", "-output_name", "fom"]
    sm, bdt, cmd = cc.run_boltrom(args, a.ranks, work / "b-cycle.json", work / "b-cycle.log")
    with h5py.File(work / "b-cycle" / "fom.h5", "r") as f:
        ub = np.array(f["/fom/probe"]).ravel()
        slip_b = np.array(f["/fom/slipping"]).ravel()
        plate_b = np.array(f["/fom/pair_force/plate2_plate1"])
    if len(ub) != n + 1:
        raise RuntimeError(f"hysteresis: boltrom gave {len(ub)} points, expected {n + 1}")
    nlow = len(np.unique(mesh.surfaces["preload_lower"]))
    fnode = sm["preload"]["force"] * sm["preload"]["layer_force_scale"] / nlow
    E = {pair: min(cc.MATERIALS[cc.PART_MATERIAL[p]][0] for p in cc.pair_parts(mesh, pair)) for pair in cc.PAIRS}
    mu = {pair: mu_v for pair in cc.PAIRS}
    stick = {pair: a.friction_stick * E[pair] for pair in cc.PAIRS}
    E_al = cc.MATERIALS["aluminium"][0]
    dat, cdt, tries = run_ccx_retried(work, "cycle", deck_cycle(mesh, fnode, a.slope * E_al, mu, stick, F, m),
                                      a.cycle_max_iterations, a.cycle_attempts)
    disp = [(t, list(d.values())[0][0]) for t, d in cc.dat_displacements(dat) if t is not None]
    u0 = [u for t, u in disp if abs(t - 1.0) < 1e-9]
    incs = {}
    for t, u in disp:
        k = (t - 1.0) * n
        if t > 1.0 + 1e-9 and abs(k - round(k)) < 1e-3:  # the .dat prints times to 7 digits
            incs[int(round(k))] = u
    if not u0 or sorted(incs) != list(range(1, n + 1)):
        raise RuntimeError(f"hysteresis: ccx gave the increments {sorted(incs)}, expected 1 .. {n}")
    uc = np.array([u0[-1]] + [incs[k] for k in range(1, n + 1)])
    blocks = cc.frd_contact(work / "cycle.frd")
    slave = np.concatenate([mesh.pair_nodes(pair)[1] for pair in cc.PAIRS])
    slip_c = []
    for blk in blocks[-(n + 1):]:
        v = np.array([blk.get(int(t), (0.0,) * 6) for t in slave])
        p, shear = v[:, 3], np.hypot(v[:, 4], v[:, 5])
        slip_c.append(int(np.sum((p > 0) & (shear >= 0.98 * mu_v * p))))
    cpair = cc.dat_pair_forces(dat)
    loads = F * np.concatenate([[0.0], cycle_loads(m)])
    dc, db = uc - uc[0], ub - ub[0]
    area_c, area_b = loop_area(loads[m:], dc[m:]), loop_area(loads[m:], db[m:])
    rows = []
    for k in range(n + 1):
        tc = min(cpair, key=lambda s: abs(s - (1.0 + k / n))) if cpair else None
        cn, cs = (cpair[tc]["plate2_plate1"][1], cpair[tc]["plate2_plate1"][2]) if tc is not None else (np.nan, np.nan)
        fb = plate_b[k]
        bs = float(np.hypot(fb[0], fb[1]))
        rows.append(dict(load=float(loads[k]), ccx=float(dc[k]), boltrom=float(db[k]), ccx_slipping=slip_c[k],
                         boltrom_slipping=int(slip_b[k]), ccx_plate_ratio=float(cs / (mu_v * abs(cn))),
                         boltrom_plate_ratio=bs / (mu_v * abs(float(fb[3])))))
    # macro-slip: the plate interface's shear at a.macro_slip times mu times its normal force; each
    # branch starts sticking at its turning point, so the first such increment in it is its onset
    onset = {}
    for branch, (lo, hi) in (("loading", (1, m + 1)), ("unloading", (m + 1, 3 * m + 1)), ("reloading", (3 * m + 1, n + 1))):
        onset[branch] = {code: first_at([w[f"{code}_plate_ratio"] for w in rows], loads, lo, hi, a.macro_slip)
                         for code in ("ccx", "boltrom")}
    r = dict(load=F, quarter=m, increments=n, mu=mu_v, macro_slip_ratio=a.macro_slip, points_compared=n + 1, rows=rows, area_ccx=area_c,
             area_boltrom=area_b, area_rel=abs(area_b - area_c) / abs(area_c), onset=onset,
             ccx_seconds=cdt, ccx_attempts=tries, boltrom_seconds=bdt, contact_points=sm["fom"]["contact_points"],
             command=" ".join(str(c) for c in cmd))
    res["hysteresis"] = r
    if a.tol_cycle_area is not None:
        res["checks"].append(dict(name="cycle loop area", ccx=area_c, boltrom=area_b, rel=r["area_rel"],
                                  tol=a.tol_cycle_area, ok=r["area_rel"] <= a.tol_cycle_area))
    for branch, o in onset.items():
        kc, kb = o["ccx"][0], o["boltrom"][0]
        ok = kc is not None and kb is not None and abs(kc - kb) <= 1
        res["checks"].append(dict(name=f"cycle macro-slip, {branch}", ccx=kc, boltrom=kb,
                                  rel=float(abs(kc - kb)) if ok else float("inf"), tol=1.0, ok=ok))
    print_hysteresis(r)
    return r


def print_hysteresis(r):
    print(f"\naxial load cycle with friction (mu {r['mu']:g}, load point held; 0 -> +F -> -F -> +F, F = {r['load']:g} N, "
          f"{r['quarter']} increments a quarter)")
    print(f"{'inc':>4s} {'load [N]':>9s} {'ccx u_x [um]':>13s} {'boltrom [um]':>13s} {'slipping ccx/boltrom':>21s} "
          f"{'plate S/muN ccx/boltrom':>24s}")
    for k, w in enumerate(r["rows"]):
        print(f"{k:4d} {w['load']:9.1f} {w['ccx'] * 1e6:13.4f} {w['boltrom'] * 1e6:13.4f} "
              f"{w['ccx_slipping']:10d}/{w['boltrom_slipping']:<10d} {w['ccx_plate_ratio']:11.3f}/{w['boltrom_plate_ratio']:<11.3f}")
    print(f"loop area (dissipation per cycle): ccx {r['area_ccx']:.6g} J, boltrom {r['area_boltrom']:.6g} J, "
          f"rel. {r['area_rel']:.2e}")
    for b, o in r["onset"].items():
        print(f"macro-slip ({b}; the plate interface at {r['macro_slip_ratio']:g} mu N): ccx from increment {o['ccx'][0]} "
              f"({o['ccx'][1]} N), boltrom from {o['boltrom'][0]} ({o['boltrom'][1]} N)")
    print(f"ccx {r['ccx_seconds']:.1f} s (attempt {r['ccx_attempts']}), boltrom {r['boltrom_seconds']:.1f} s")


# ---------------------------------------------------------------------------
# A load cycle with friction on two pressed blocks
# ---------------------------------------------------------------------------
BLOCKS_CYCLE_PROBE = (0.0, 0.0, 0.01)  # boltrom's probe: the first node of contact_upper_lower_a


def deck_blocks_cycle(mesh, press_node_force, slope, mu, stick, load, m):
    """The two blocks with surface-to-surface penalty contact and Coulomb friction on
    upper_lower (slave: side b, the lower block's top; master: side a), the top face held in x
    and y; step 1 the press (equal forces down on the top face's nodes, boltrom's preload layer),
    step 2 the load along x on the upper block's bottom face (by area, as boltrom spreads it)
    round the cycle: *STATIC, DIRECT in 5 m increments through an *AMPLITUDE of the load
    factors. Returns the deck and the probe node."""
    a_nodes = np.unique(mesh.surfaces[f"contact_{PAIR}_a"])
    probe = int(a_nodes[np.argmin(np.linalg.norm(mesh.xyz(a_nodes) - BLOCKS_CYCLE_PROBE, axis=1))])
    out = blocks_model(mesh) + ["*BOUNDARY", "TOP, 1, 2", "*NSET, NSET=PROBE", str(probe)]
    for side in "ab":
        out.append(f"*SURFACE, NAME=S_{PAIR}_{side}, TYPE=ELEMENT")
        out += [f"{e}, S{f}" for e, f in mesh.face_surface(mesh.surfaces[f"contact_{PAIR}_{side}"])]
    out += ["*SURFACE INTERACTION, NAME=SI", "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR", f"{slope:.6g}",
            "*FRICTION", f"{mu:.6g}, {stick:.6g}", "*CONTACT PAIR, INTERACTION=SI, TYPE=SURFACE TO SURFACE",
            f"S_{PAIR}_b, S_{PAIR}_a"]
    n = 5 * m
    out += ["*AMPLITUDE, NAME=CYCLE", "0., 0."] + [f"{(k + 1) / n:.15g}, {ccx_number(v)}" for k, v in enumerate(cycle_loads(m))]
    prints = f"*NODE PRINT, NSET=PROBE\nU\n*CONTACT PRINT, SLAVE=S_{PAIR}_b, MASTER=S_{PAIR}_a\nCF\n"
    w = face_weights(mesh, f"contact_{PAIR}_a")
    s = "\n".join(out) + "\n"
    s += (f"*STEP, INC=1000\n*STATIC\n1.0, 1.0\n*CLOAD\nTOP, 3, {-press_node_force:.15g}\n" + prints + "*END STEP\n")
    s += (f"*STEP, INC={n + 10}\n*STATIC, DIRECT\n{1.0 / n:.15g}, 1.0\n*CLOAD, AMPLITUDE=CYCLE\n"
          + "".join(f"{t}, 1, {load * v:.15g}\n" for t, v in sorted(w.items())) + prints + "*END STEP\n")
    return s, probe


CYCLE_BRANCHES = (("loading", 1), ("unloading", -1), ("reloading", 1))


def branch_ranges(m):
    """Increments of the cycle's three branches: [start, stop) each, from the turning point
    before it (0 -> +F, +F -> -F, -F -> +F)."""
    n = 5 * m
    return {"loading": (0, m + 1), "unloading": (m, 3 * m + 1), "reloading": (3 * m, n + 1)}


def slip_load(ratio, loads, lo, hi, sign, level):
    """The load at which the interface's friction force, signed along the branch, first reaches
    `level` times mu N in increments lo .. hi - 1: linear between the two increments about it."""
    r = sign * np.asarray(ratio)
    for k in range(lo + 1, hi):
        if r[k] >= level:
            t = (level - r[k - 1]) / (r[k] - r[k - 1]) if r[k] != r[k - 1] else 1.0
            return float(loads[k - 1] + t * (loads[k] - loads[k - 1]))
    return None


def run_hysteresis_blocks(a, work, res):
    """Two steel blocks (scripts/mesh-joint --kind blocks, --cycle-blocks-level) pressed by BLOCKS_PRESS,
    Coulomb friction mu (--friction-mu) with the same elastic stick in both codes; the top face
    held in x and y, so that the upper block is a shear spring in parallel with the interface's
    friction; the load along x on the upper block's bottom face taken 0 -> +F -> -F -> +F
    (--cycle-blocks-load, --cycle-blocks-quarter). boltrom -ts_quasistatic with a sine load
    sampled at ccx's increments. Compares u_x of the probe (a corner of the loaded face) at every
    increment, the loop's area, the load at which the interface slides as a whole in each branch,
    and the friction force while it slides against mu times the press."""
    m, F, mu_v, N = a.cycle_blocks_quarter, a.cycle_blocks_load, a.friction_mu, BLOCKS_PRESS
    n = 5 * m
    lev = f"{a.cycle_blocks_level:g}"
    msh = work / f"blocks-L{lev}.msh"
    if not msh.exists():
        subprocess.run([sys.executable, str(ROOT / "scripts" / "mesh-joint"), "--kind", "blocks", "--level", lev,
                        "--output", str(msh)], check=True, capture_output=True)
    mesh = cc.Mesh(msh)
    out = work / "b-cycle-blocks"
    args = ["-mesh", msh, "-element", "full", "-fom", "true", "-rom", "false", "-static", "false", "-modal_nev", "0",
            "-contact_law", "coulomb", "-contact_friction", mu_v, "-contact_stick_stiffness_factor", a.friction_stick,
            "-preload_lower_group", "clamp", "-preload_upper_group", "top", "-preload_force", N, "-preload_axis", "0,0,1",
            "-ts_quasistatic", "-load_history", "sine", "-load_frequency", 1.0, "-ts_dt", 1.0 / (4 * m),
            "-ts_end", n / (4 * m), "-load_group", f"contact_{PAIR}_a", "-load_direction", "1,0,0", "-load_force", F,
            "-probe_group", f"contact_{PAIR}_a", "-probe_component", 0, "-support_group", "top",
            "-support_components", "0,1", "-output_dir", out, "-output_name", "fom"]
    sm, bdt, cmd = cc.run_boltrom(args, a.ranks, work / "b-cycle-blocks.json", work / "b-cycle-blocks.log")
    with h5py.File(out / "fom.h5", "r") as f:
        ub = np.array(f["/fom/probe"]).ravel()
        pf = np.array(f[f"/fom/pair_force/{PAIR}"])
        slip_b = np.array(f["/fom/slipping"]).ravel()
        dissipated = np.array(f["/fom/dissipated"]).ravel()
        work_ext = np.array(f["/fom/energy_accounting/external_work"]).ravel()
        X = np.array(f["/geometry/vertices"])
        U = np.array(f["/vertex_fields/fom_final_displacement"])
    if len(ub) != n + 1:
        raise RuntimeError(f"hysteresis blocks: boltrom gave {len(ub)} points, expected {n + 1}")
    at = np.linalg.norm(X - np.array(BLOCKS_CYCLE_PROBE), axis=1) < 1e-12  # the node of each block there
    if not np.any(np.abs(U[at, 0] - ub[-1]) <= 1e-12 * max(abs(ub[-1]), 1e-30)):
        raise RuntimeError(f"hysteresis blocks: boltrom's probe is not the node at {BLOCKS_CYCLE_PROBE}")
    fnode = sm["preload"]["force"] * sm["preload"]["layer_force_scale"] / len(np.unique(mesh.surfaces["top"]))
    deck, probe = deck_blocks_cycle(mesh, fnode, a.cycle_blocks_slope * E_STEEL, mu_v, a.friction_stick * E_STEEL, F, m)
    dat, cdt, tries = run_ccx_retried(work, "cycle-blocks", deck, a.cycle_max_iterations, 1)
    disp = [(t, d[probe][0]) for t, d in cc.dat_displacements(dat) if t is not None]
    cpair = cc.dat_pair_forces(dat)
    u0 = [u for t, u in disp if abs(t - 1.0) < 1e-9]
    incs = {}
    for t, u in disp:
        k = (t - 1.0) * n
        if t > 1.0 + 1e-9 and abs(k - round(k)) < 1e-3:
            incs[int(round(k))] = u
    if not u0 or sorted(incs) != list(range(1, n + 1)):
        raise RuntimeError(f"hysteresis blocks: ccx gave the increments {sorted(incs)}, expected 1 .. {n}")
    uc = np.array([u0[-1]] + [incs[k] for k in range(1, n + 1)])
    fc = []
    for k in range(n + 1):
        tc = min(cpair, key=lambda s: abs(s - (1.0 + k / n)))
        if abs(tc - (1.0 + k / n)) > 1e-6:
            raise RuntimeError(f"hysteresis blocks: no ccx contact statistics at increment {k}")
        (fx, _fy, _fz), cn, cs = cpair[tc][PAIR]
        fc.append((float(np.sign(fx) * cs), float(-cn)))  # friction along x (signed), normal force
    fc = np.array(fc)
    fb = np.column_stack([np.sign(pf[:, 0]) * np.hypot(pf[:, 0], pf[:, 1]), -pf[:, 3]])
    loads = F * np.concatenate([[0.0], cycle_loads(m)])
    dc, db = uc - uc[0], ub - ub[0]
    ratio = {"ccx": fc[:, 0] / (mu_v * fc[:, 1]), "boltrom": fb[:, 0] / (mu_v * fb[:, 1])}
    rows = [dict(load=float(loads[k]), ccx=float(dc[k]), boltrom=float(db[k]), ccx_friction=float(fc[k, 0]),
                 boltrom_friction=float(fb[k, 0]), ccx_normal=float(fc[k, 1]), boltrom_normal=float(fb[k, 1]),
                 ccx_ratio=float(ratio["ccx"][k]), boltrom_ratio=float(ratio["boltrom"][k]), boltrom_slipping=int(slip_b[k]))
            for k in range(n + 1)]
    area_c, area_b = loop_area(loads[m:], dc[m:]), loop_area(loads[m:], db[m:])
    ranges = branch_ranges(m)
    onset = {b: {code: slip_load(ratio[code], loads, *ranges[b], sign, a.macro_slip) for code in ("ccx", "boltrom")}
             for b, sign in CYCLE_BRANCHES}
    # while every contact point slips in boltrom the interface slides as a whole: its friction
    # force is mu N, in both codes
    sliding = [k for k in range(1, n + 1) if slip_b[k] == sm["fom"]["contact_points"]]
    slip_force = {code: float(max(abs(abs(ratio[code][k]) - 1.0) for k in sliding)) if sliding else float("inf")
                  for code in ("ccx", "boltrom")}
    normal = {"ccx": float(np.abs(fc[:, 1] / N - 1).max()), "boltrom": float(np.abs(fb[:, 1] / N - 1).max())}
    diff = np.abs(db - dc)
    r = dict(level=a.cycle_blocks_level, load=F, press=N, quarter=m, increments=n, mu=mu_v, stick=a.friction_stick, slope=a.cycle_blocks_slope,
             macro_slip_ratio=a.macro_slip, points_compared=n + 1, rows=rows,
             u_max_diff=float(diff.max()), u_range_ccx=float(np.ptp(dc)), u_rel=float(diff.max() / np.ptp(dc)),
             u_worst=int(np.argmax(diff)), area_ccx=area_c, area_boltrom=area_b,
             area_rel=abs(area_b - area_c) / abs(area_c),
             boltrom_dissipated_cycle=float(dissipated[n] - dissipated[m]),
             boltrom_external_work_cycle=float(work_ext[n] - work_ext[m]),
             onset=onset, stick_share=float(fb[1, 0] / loads[1]),
             onset_stick_limit={"loading": float(mu_v * N / (fb[1, 0] / loads[1])),
                                "unloading": float(F - 2 * mu_v * N / (fb[1, 0] / loads[1]))},
             sliding_increments=sliding, slip_force_rel=slip_force, normal_rel=normal,
             contact_points=sm["fom"]["contact_points"], ccx_seconds=cdt, boltrom_seconds=bdt,
             command=" ".join(str(c) for c in cmd))
    res["hysteresis_blocks"] = r
    ch = res["checks"]
    ch.append(dict(name="cycle blocks u_x history", ccx=r["u_range_ccx"], boltrom=r["u_range_ccx"] + r["u_max_diff"],
                   rel=r["u_rel"], tol=a.tol_cycle_blocks_u, ok=r["u_rel"] <= a.tol_cycle_blocks_u))
    ch.append(dict(name="cycle blocks loop area", ccx=area_c, boltrom=area_b, rel=r["area_rel"],
                   tol=a.tol_cycle_blocks_area, ok=r["area_rel"] <= a.tol_cycle_blocks_area))
    for b, o in onset.items():
        ok = o["ccx"] is not None and o["boltrom"] is not None
        rel = abs(o["ccx"] - o["boltrom"]) / F if ok else float("inf")
        ch.append(dict(name=f"cycle blocks slip load, {b}", ccx=o["ccx"], boltrom=o["boltrom"], rel=rel,
                       tol=a.tol_cycle_blocks_onset, ok=ok and rel <= a.tol_cycle_blocks_onset))
    for code in ("ccx", "boltrom"):
        x = slip_force[code]
        ch.append(dict(name=f"cycle blocks friction = mu N, {code}", ccx=mu_v * N, boltrom=mu_v * N * (1 + x), rel=x,
                       tol=a.tol_cycle_blocks_slip, ok=len(sliding) > 0 and x <= a.tol_cycle_blocks_slip))
    print_hysteresis_blocks(r)
    return r


def print_hysteresis_blocks(r):
    print(f"\nload cycle with friction on two pressed blocks (level {r['level']:g}; mu {r['mu']:g}, press {r['press']:g} N, top face held in x, y; "
          f"0 -> +F -> -F -> +F on the upper block's bottom face, F = {r['load']:g} N, {r['quarter']} increments a quarter)")
    print(f"{'inc':>4s} {'load [N]':>9s} {'ccx u_x [nm]':>13s} {'boltrom [nm]':>13s} {'friction ccx/boltrom [N]':>25s} "
          f"{'F/(mu N) ccx/boltrom':>21s} {'slipping':>8s}")
    for k, w in enumerate(r["rows"]):
        print(f"{k:4d} {w['load']:9.2f} {w['ccx'] * 1e9:13.3f} {w['boltrom'] * 1e9:13.3f} {w['ccx_friction']:12.3f}/"
              f"{w['boltrom_friction']:<12.3f} {w['ccx_ratio']:10.4f}/{w['boltrom_ratio']:<10.4f} {w['boltrom_slipping']:5d}/{r['contact_points']}")
    print(f"u_x: largest difference {r['u_max_diff'] * 1e9:.3f} nm at increment {r['u_worst']}, {r['u_rel']:.2e} of ccx's range "
          f"({r['u_range_ccx'] * 1e9:.1f} nm)")
    print(f"loop area: ccx {r['area_ccx']:.6g} J, boltrom {r['area_boltrom']:.6g} J, rel. {r['area_rel']:.2e}; boltrom's "
          f"friction dissipation over the cycle {r['boltrom_dissipated_cycle']:.6g} J, its load's work {r['boltrom_external_work_cycle']:.6g} J")
    for b, o in r["onset"].items():
        c, w = o["ccx"], o["boltrom"]
        print(f"slides as a whole ({b}; friction at {r['macro_slip_ratio']:g} mu N): ccx at "
              + (f"{c:.2f} N" if c is not None else "never") + ", boltrom at " + (f"{w:.2f} N" if w is not None else "never"))
    print(f"(while the interface sticks it takes {r['stick_share']:.4f} of the load in boltrom's first increment: sliding cannot "
          f"start before {r['onset_stick_limit']['loading']:.2f} N on loading and {r['onset_stick_limit']['unloading']:.2f} N "
          "after a turn; micro-slip at its rim delays it)")
    print(f"friction while sliding (increments {r['sliding_increments']}): largest |F/(mu N) - 1| ccx {r['slip_force_rel']['ccx']:.1e}, "
          f"boltrom {r['slip_force_rel']['boltrom']:.1e}; normal force against the press: ccx {r['normal_rel']['ccx']:.1e}, "
          f"boltrom {r['normal_rel']['boltrom']:.1e}")
    print(f"ccx {r['ccx_seconds']:.1f} s, boltrom {r['boltrom_seconds']:.1f} s")
