"""Accuracy against cost: the published study (docs/accuracy.md and docs/img/accuracy_*.png).

Run from the repository root with beltrs installed::

    python benches/accuracy_study.py            # full study, about 3-5 minutes
    python benches/accuracy_study.py --quick    # takeup-displacement ladder only (seconds)
    python benches/accuracy_study.py --out DIR  # write the page and plots to DIR
    python benches/accuracy_study.py --only integrators  # case K, RKF45 against central
                                                         # differences; replaces that section

Every table comes from :func:`beltrs.study.accuracy_cost`; wall times are from this run on
this machine (one thread) and include building, stabilising and running each setting.
"""

from __future__ import annotations

import argparse
import math
import pathlib
import platform
import sys
import time
from dataclasses import replace
from typing import Any

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import beltrs  # noqa: E402
from beltrs import study  # noqa: E402
from beltrs.analytic import takeup_step_response  # noqa: E402
from beltrs.analysis import low_pass, probe_run  # noqa: E402
from bench_scenes import KUBAS_RADIUS, KUBAS_TORQUE, kubas_drive  # noqa: E402

ROOT = HERE.parent
H = beltrs.scenes.hustrulid_loop
KUBAS_DURATION = 0.7  # s: torque ramp to 0.3 s, then 0.4 s of steady running
KUBAS_WINDOW = 0.2  # s averaged at the end
# Case K starts from rest at preload: 1e-4 of the largest tension (0.06 N) is static enough.
K_STAB = {"tolerance": 1e-4, "max_steps": 300_000}


def plot(tables: list[tuple[str, study.StudyTable]], path: pathlib.Path, title: str, scale: float = 1.0,
         unit: str = "", grid: list[tuple[float, float, str]] | None = None) -> None:
    """Log-log error against wall time, one line per ladder; optional scatter of a grid with
    its Pareto front."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    markers = "osD^v<>"
    for k, (label, t) in enumerate(tables):
        ok = t.error > 0
        ax.loglog(t.wall_time[ok], t.error[ok] * scale, marker=markers[k % len(markers)], label=label)
        for w, e, s in zip(t.wall_time[ok], t.error[ok] * scale, t.setting[ok]):
            ax.annotate(f"{s:.3g}", (w, e), textcoords="offset points", xytext=(4, 4), fontsize=7)
    if grid:
        w = np.array([g[0] for g in grid])
        e = np.array([g[1] for g in grid]) * scale
        ax.loglog(w, e, "k.", alpha=0.4, label="grid (elements x dt fraction)")
        front = study.pareto_front(w, e)
        ax.loglog(w[front], e[front], "k--", lw=1, label="Pareto front")
        for i in front:
            ax.annotate(grid[i][2], (w[i], e[i]), textcoords="offset points", xytext=(4, -10), fontsize=7)
    ax.set_xlabel("wall time per answer, s")
    ax.set_ylabel(f"error{(' (' + unit + ')') if unit else ''}")
    ax.set_title(title, fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def kubas_quantities() -> tuple[study.Quantity, study.Quantity]:
    exact = KUBAS_TORQUE / KUBAS_RADIUS
    diff = study.tension_difference("drive", "driven", KUBAS_DURATION, window=KUBAS_WINDOW, exact=exact)
    sl = study.slip("drive", "driven", KUBAS_DURATION, window=KUBAS_WINDOW)
    return diff, sl


# Case G ladder: the conveyor shortened to 200 m (each setting of the 972 m one costs 1-16
# minutes at these meshes); Harrison start in 10 s, tight side read 10 m before the head.
G_LENGTH = 200.0
G_DURATION = 11.0  # s: the 10 s ramp and 1 s at speed
G_INTERVAL = 0.005  # s
G_CUTOFF = 2.0  # Hz
G_STAB = {"tolerance": 1e-5, "max_steps": 400_000}
G_RAW: dict[tuple[int, float], float] = {}  # (nodes, dt) -> raw peak, filled by the quantity


def case_g_scene(**kw: Any) -> beltrs.Scene:
    """The shortened conveyor with its default start (Harrison, 10 s to 2 m/s)."""
    scene = beltrs.scenes.guo_wang_conveyor(length=G_LENGTH, **kw)
    # The study is the nodal contact's (its O(θ²) chord ladder): keep it against the
    # builder's wrap default (session 8).
    return replace(scene, belt=replace(scene.belt, pulley_contact="nodes"))


def case_g_peak() -> study.Quantity:
    """Peak tight-side tension of the start, below 2 Hz (the raw peak goes to G_RAW)."""
    probe = [(G_LENGTH - 10.0, beltrs.scenes.GUO_WANG["drum_radius"])]
    series: dict[int, np.ndarray] = {}

    def run(sim: beltrs.Simulation) -> None:
        series[id(sim)] = probe_run(sim, probe, G_DURATION, G_INTERVAL)["tension"][:, 0]

    def measure(sim: beltrs.Simulation) -> float:
        t1 = series.pop(id(sim))
        G_RAW[(sim.nodes, sim.dt)] = float(t1.max())
        return float(low_pass(t1, G_INTERVAL, G_CUTOFF).max())

    return study.Quantity("peak start-up tension below 2 Hz", "N", measure, run=run)


# --- Case K: RKF45 against central differences, both formulations -------------------------
# Ramp 0.05 s, run 0.1 s, averages over the last 0.04 s, sampled every ms; creep friction on both
# pulleys at Delta_v = 0.1 m/s, Delta_max 0.1 mm (at the default Delta_v = 1 mm/s RKF45's step is
# 5.8e-9 s, docs/kubas.md: the sticking contacts' damping rate 1.5 mu_s N/(m Delta_v) sets it).
I_RAMP, I_DURATION, I_WINDOW, I_SAMPLE = 0.05, 0.1, 0.04, 1e-3
I_DV, I_DMAX = 0.1, 1e-4
I_FRACTIONS = [0.8, 0.4, 0.2]
I_TOLERANCES = [1e-4, 1e-5, 1e-6, 1e-7, 1e-8]
I_FORMULATIONS = ("node", "rigid_body")
I_STAB = {"tolerance": 1e-4, "max_steps": 300_000}
I_NOTES: dict[str, str] = {}  # formulation -> why its RKF45 ladder did not run


def case_k_creep(formulation: str, time_step_fraction: float = 0.5) -> beltrs.Scene:
    """Case K with creep friction: the node model (``kubas_drive``, 150 elements, linear
    contact, uncalibrated preload) or Kubas's rigid bodies (``kubas_case_k``, 150 bodies)."""
    creep = beltrs.Friction(model="creep", static=1.05, kinetic=1.0, transition_speed=I_DV, creep_limit=I_DMAX)
    if formulation == "node":
        scene = kubas_drive(150, time_step_fraction=time_step_fraction, calibrate=False)
        ramp = beltrs.Drive(time=[0.0, I_RAMP], torque=[0.0, KUBAS_TORQUE])
        scene = replace(scene, pulleys=[replace(scene.pulleys[0], drive=ramp), scene.pulleys[1]])
    else:
        scene = beltrs.scenes.kubas_case_k(ramp_time=I_RAMP)
        scene = replace(scene, solver=replace(scene.solver, time_step_fraction=time_step_fraction))
    return replace(scene, pulleys=[replace(p, friction=creep) for p in scene.pulleys])


def integrator_quantities() -> list[study.Quantity]:
    diff = study.tension_difference("drive", "driven", I_DURATION, window=I_WINDOW, record_interval=I_SAMPLE)
    sl = study.slip("drive", "driven", I_DURATION, window=I_WINDOW, record_interval=I_SAMPLE)
    return [diff, sl]


def integrator_ladders(T: dict[str, study.StudyTable], tolerances: list[float], fractions: list[float]) -> None:
    """Fill T['int_<formulation>_<cd|rk>_<diff|slip>'] (RKF45 skipped, with the reason in
    I_NOTES, where the engine refuses it)."""
    for f in I_FORMULATIONS:
        t0 = time.perf_counter()
        make = lambda f=f, **kw: case_k_creep(f, **kw)  # noqa: E731
        T[f"int_{f}_cd_diff"], T[f"int_{f}_cd_slip"] = study.accuracy_costs(
            make, integrator_quantities(), "time_step_fraction", fractions, stabilise_options=I_STAB
        )
        print(f"int_{f}_cd: {time.perf_counter() - t0:.1f} s", flush=True)
        t0 = time.perf_counter()
        try:
            T[f"int_{f}_rk_diff"], T[f"int_{f}_rk_slip"] = study.accuracy_costs(
                make, integrator_quantities(), "rkf_tolerance", tolerances, stabilise_options=I_STAB
            )
        except beltrs.SceneError as err:
            I_NOTES[f] = str(err)
        print(f"int_{f}_rk: {time.perf_counter() - t0:.1f} s", flush=True)


def common_reference(T: dict[str, study.StudyTable], f: str, what: str) -> tuple[float, str]:
    """The tightest RKF45 run if there is one, else the smallest central-difference step."""
    if f"int_{f}_rk_{what}" in T:
        t = T[f"int_{f}_rk_{what}"]
        return float(t.value[-1]), f"RKF45 at {t.setting[-1]:.0e}"
    t = T[f"int_{f}_cd_{what}"]
    return float(t.value[-1]), f"central differences at {t.setting[-1]:g}"


def matched_table(T: dict[str, study.StudyTable], f: str) -> str:
    """For each RKF45 rung, the cheapest central-difference rung as accurate in both T1 - T2
    and slip (against the common reference), and the wall-time ratio."""
    if f"int_{f}_rk_diff" not in T:
        return ""
    (rd, kind), (rs, _) = common_reference(T, f, "diff"), common_reference(T, f, "slip")
    cd_d, cd_s = T[f"int_{f}_cd_diff"].against(rd, kind), T[f"int_{f}_cd_slip"].against(rs, kind)
    rk_d, rk_s = T[f"int_{f}_rk_diff"].against(rd, kind), T[f"int_{f}_rk_slip"].against(rs, kind)
    lines = ["| RKF45 tolerance | errors T1 − T2 (N); slip (%) | wall (s) | accepted steps | cheapest CD fraction "
             "as accurate | its errors | wall (s) | RKF45 / CD wall |", "|---:|---|---:|---:|---:|---|---:|---:|"]
    for i, row in enumerate(rk_d.rows[:-1]):  # the last is the reference itself
        es = rk_s.rows[i].error
        ok = [j for j, r in enumerate(cd_d.rows) if r.error <= row.error and cd_s.rows[j].error <= es]
        steps = row.node_steps // row.nodes
        mine = f"| {row.setting:.0e} | {row.error:.3g}; {100 * es:.3g} | {row.wall_time:.3g} | {steps} |"
        if ok:
            j = min(ok, key=lambda j: cd_d.rows[j].wall_time)
            c = cd_d.rows[j]
            lines.append(f"{mine} {c.setting:g} | {c.error:.3g}; {100 * cd_s.rows[j].error:.3g} | "
                         f"{c.wall_time:.3g} | {row.wall_time / c.wall_time:.2g} |")
        else:
            lines.append(f"{mine} none in the ladder | | | |")
    return "\n".join(lines)


def integrator_section(T: dict[str, study.StudyTable]) -> list[str]:
    """The page section (between markers, so ``--only integrators`` can replace it alone)."""
    L = ["<!-- integrators -->", "## Case K: RKF45 against central differences", ""]
    add = L.append
    add(f"Case K with creep friction (Δv = {I_DV:g} m/s, Δmax = {I_DMAX * 1e3:g} mm, µs = 1.05, µk = 1.0) "
        "for both belt "
        f"formulations at 150 elements/bodies: the node model (`kubas_drive`, linear contact 1e7 N/m, preload "
        f"uncalibrated) and Kubas's rigid bodies (`beltrs.scenes.kubas_case_k`, nonlinear contact). Drive "
        f"torque ramped to 15 N·m over {I_RAMP:g} s, run {I_DURATION:g} s, averages over the last "
        f"{I_WINDOW:g} s, sampled every {I_SAMPLE * 1e3:g} ms. Central differences (CD) at fractions "
        f"{', '.join(f'{v:g}' for v in I_FRACTIONS)} of the stable step (creep friction with its stick limit); "
        f"RKF45 at relative tolerances {', '.join(f'{v:.0e}' for v in I_TOLERANCES)} (absolute tolerance "
        "1e-11, the creep law resolved). The mesh is the same in every row, so the errors here are the time "
        "integration's alone: they are measured against one common reference per formulation (the tightest "
        "RKF45 run; the smallest CD step where RKF45 did not run), not against M/r (the mesh's error of "
        "T₁ − T₂ is in the case K table above). *node-steps* count accepted steps; an RKF45 step costs six "
        "force evaluations, a CD step one. Wall includes the static relaxation. Command: "
        "`python benches/accuracy_study.py --only integrators`. Why Δv = 0.1 m/s: RKF45 resolves the "
        "creep law, whose sticking contacts have the damping rate 1.5·µs·N/(m·Δv), so its step is "
        "proportional to Δv (5.8e-9 s at the default 1 mm/s, 10⁷ steps per simulated second, docs/kubas.md); "
        "at 0.1 m/s both integrators run the same law at steps of the same size. The answers at this Δv are "
        "not the paper's (the creep range covers the whole slip arcs): the table compares integrators on one "
        "law, not the law against the paper.")
    add("")
    for f in I_FORMULATIONS:
        add(f"### {f}")
        add("")
        for what, scale, unit in (("diff", 1.0, "N"), ("slip", 100.0, "%")):
            ref, kind = common_reference(T, f, what)
            for key in (f"int_{f}_cd_{what}", f"int_{f}_rk_{what}"):
                if key in T:
                    add(T[key].against(ref, kind).to_markdown(scale, unit))
                    add("")
        if f in I_NOTES:
            add(f"RKF45 not run: the engine refuses it for this scene: {I_NOTES[f]}")
            add("")
        m = matched_table(T, f)
        if m:
            add("At matched error (the cheapest CD setting whose errors in T₁ − T₂ *and* slip are both at most "
                "the RKF45 row's):")
            add("")
            add(m)
            add("")
    add("![integrators](img/accuracy_kubas_integrators.png)")
    add("")
    add("<!-- /integrators -->")
    return L


def plot_integrators(T: dict[str, study.StudyTable], img: pathlib.Path) -> None:
    lines = []
    for f in I_FORMULATIONS:
        ref, kind = common_reference(T, f, "diff")
        for tag, name in (("cd", "CD, fraction"), ("rk", "RKF45, tolerance")):
            if f"int_{f}_{tag}_diff" in T:
                lines.append((f"{f}: {name}", T[f"int_{f}_{tag}_diff"].against(ref, kind)))
    plot(lines, img / "accuracy_kubas_integrators.png", "Case K, creep friction: T1 - T2 error vs wall time",
         unit="N")


def splice(path: pathlib.Path, section: list[str]) -> None:
    """Replace the integrators section of an existing page (or append it before the
    conclusions)."""
    text = path.read_text(encoding="utf-8")
    block = "\n".join(section)
    if "<!-- integrators -->" in text:
        a = text.index("<!-- integrators -->")
        b = text.index("<!-- /integrators -->") + len("<!-- /integrators -->")
        text = text[:a] + block + text[b:]
    else:
        a = text.index("## Conclusions")
        text = text[:a] + block + "\n\n" + text[a:]
    path.write_text(text, encoding="utf-8")


def main(argv: list[str] | None = None) -> dict[str, study.StudyTable]:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="takeup-displacement ladder only (smoke test)")
    ap.add_argument("--out", default=str(ROOT / "docs"), help="directory for accuracy.md and img/ (default docs/)")
    ap.add_argument("--only", choices=["integrators"],
                    help="run only this section and replace it in an existing accuracy.md")
    args = ap.parse_args(argv)
    out = pathlib.Path(args.out)
    img = out / "img"
    started = time.perf_counter()
    T: dict[str, study.StudyTable] = {}
    if args.only == "integrators":
        integrator_ladders(T, I_TOLERANCES, I_FRACTIONS)
        plot_integrators(T, img)
        splice(out / "accuracy.md", integrator_section(T))
        print(f"replaced the integrators section of {out / 'accuracy.md'} in {time.perf_counter() - started:.0f} s")
        return T

    def run(key: str, *a: Any, **kw: Any) -> study.StudyTable:
        t0 = time.perf_counter()
        T[key] = study.accuracy_cost(*a, **kw)
        print(f"{key}: {time.perf_counter() - t0:.1f} s", flush=True)
        return T[key]

    elements = [100, 200, 400] if args.quick else [100, 200, 400, 800]
    run("takeup_elements", H, study.takeup_displacement(), values=elements)
    if not args.quick:
        run("tension_A", H, study.hustrulid_tension("A"), values=elements)
        run("tension_C", H, study.hustrulid_tension("C"), values=elements)
        # Contact ladders against Richardson references (the contact part of the error alone).
        # 6e8 N/m and stiffer do not relax in 3e5 steps at 200 elements (docs/engine.md).
        run("takeup_contact", lambda **kw: H(200, **kw), study.takeup_displacement(exact=math.nan),
            "contact_stiffness", [2e6, 2e7, 2e8])
        run("tension_contact", lambda **kw: H(200, **kw), replace(study.hustrulid_tension("A"), exact=None),
            "contact_stiffness", [2e6, 2e7, 2e8])
        wave = study.hustrulid_wave_speed_quantity()
        run("wave_elements", H, wave, values=[100, 200, 400, 800])
        run("wave_dt", lambda **kw: H(200, **kw), wave, "time_step_fraction", [0.9, 0.5, 0.25, 0.125])
        grid = []
        for n in (100, 200, 400):
            # (400 elements at fraction 0.9 does not relax: docs/performance.md, known issue)
            t = study.accuracy_cost(lambda n=n, **kw: H(n, **kw), wave, "time_step_fraction", [0.8, 0.4, 0.2])
            grid += [(r.wall_time, r.error, f"{n}/{r.setting:g}") for r in t.rows]
        cw = study.counterweight_step_frequency()
        run("freq_elements", H, cw, values=[100, 200, 400])
        run("freq_dt", H, cw, "time_step_fraction", [0.9, 0.45, 0.225])
        diff, sl = kubas_quantities()
        run("kubas_diff", kubas_drive, diff, values=[75, 150, 300], stabilise_options=K_STAB)
        run("kubas_slip", kubas_drive, sl, values=[75, 150, 300], stabilise_options=K_STAB)
        run("kubas_contact", lambda **kw: kubas_drive(150, **kw), sl, "contact_stiffness", [3e6, 1e7, 3e7],
            stabilise_options=K_STAB)
        peak = case_g_peak()
        run("g_elements", case_g_scene, peak, "element_length", [0.2, 0.1, 0.05], stabilise_options=G_STAB)
        run("g_dt", case_g_scene, peak, "time_step_fraction", [0.8, 0.4, 0.2], stabilise_options=G_STAB)
        integrator_ladders(T, I_TOLERANCES, I_FRACTIONS)

    # --- plots -------------------------------------------------------------------------
    plot([("elements", T["takeup_elements"])] + ([("contact stiffness, 200 el.", T["takeup_contact"])]
         if "takeup_contact" in T else []), img / "accuracy_takeup.png",
         "Case H takeup displacement: error vs wall time", unit="m")
    if not args.quick:
        plot([("A, elements", T["tension_A"]), ("C, elements", T["tension_C"]),
              ("A, contact stiffness, 200 el.", T["tension_contact"])], img / "accuracy_tension.png",
             "Case H static tensions: error vs wall time", scale=1e-3, unit="kN")
        plot([("elements (dt fraction 0.5)", T["wave_elements"]), ("dt fraction, 200 el.", T["wave_dt"])],
             img / "accuracy_wave.png", "Case H wave speed: error vs wall time", unit="m/s", grid=grid)
        plot([("elements", T["freq_elements"]), ("dt fraction, 89 el.", T["freq_dt"])],
             img / "accuracy_frequency.png", "Case H counterweight-step frequency: error vs wall time", unit="Hz")
        plot([("T1-T2, elements", T["kubas_diff"])], img / "accuracy_kubas.png",
             "Case K (node model): T1 - T2 error vs wall time", unit="N")
        plot([("element length", T["g_elements"]), ("dt fraction, 0.2 m", T["g_dt"])], img / "accuracy_case_g.png",
             f"Case G ({G_LENGTH:g} m): peak start-up tension error vs wall time", scale=1e-3, unit="kN")
        plot_integrators(T, img)

    write_page(out / "accuracy.md", T, args.quick, time.perf_counter() - started)
    print(f"wrote {out / 'accuracy.md'} in {time.perf_counter() - started:.0f} s")
    return T


def order_range(t: study.StudyTable) -> str:
    o = t.order[~np.isnan(t.order)]
    if len(o) == 0:
        return "n/a"
    return f"{o.min():.2f}–{o.max():.2f}" if len(o) > 1 else f"{o[0]:.2f}"


def write_page(path: pathlib.Path, T: dict[str, study.StudyTable], quick: bool, wall: float) -> None:
    L: list[str] = []
    add = L.append
    add("# Accuracy against cost")
    add("")
    add("Generated by `python benches/accuracy_study.py` (do not edit by hand)"
        f"{' — QUICK MODE, takeup ladder only' if quick else ''}. beltrs {beltrs.__version__}, "
        f"Python {platform.python_version()}, {platform.machine()}, one thread; the study took {wall:.0f} s. "
        "Each row is one call of `beltrs.study.accuracy_cost`: build, stabilise (FIRE, tolerance 1e-7), "
        "run the scenario, measure. *Wall* is all of that; *node-steps* = nodes × (relaxation + dynamic "
        "steps). Orders: log(e₁/e₂)/log(h₁/h₂) against the exact answer, or from three consecutive "
        "values where the reference is Richardson-extrapolated. The machine is shared (2 cores), so wall "
        "times scatter by ±30 %; node-steps do not.")
    add("")
    add("Models covered: Hustrulid's node model (Kelvin-Voigt elements, bending springs, nodal penalty "
        "contact, stick-force friction, central differences), with speed-controlled drives, material load "
        "and DIN 22101 running resistance for case G; and, on case K with creep friction, both belt "
        "formulations (the node model and Kubas's rigid bodies with his nonlinear contact) under central "
        "differences and under adaptive RKF45 (`accuracy_cost(..., refine='rkf_tolerance')`, tolerance "
        "ladders), in the last section.")
    add("")
    t = T["takeup_elements"]
    add("## Case H: takeup displacement (static)")
    add("")
    add("Exact continuum answer −3.1410 m (`beltrs.analytic.two_pulley_takeup_statics`). The chord "
        "polygon on the pulleys is shorter than the arc by πrθ²/24 per half wrap, so the error falls as "
        f"the element angle squared. **Measured orders: {order_range(t)}.**")
    add("")
    add(t.to_markdown())
    add("")
    if "takeup_contact" in T:
        add("Contact stiffness at 200 elements (N/m; errors against the Richardson limit of infinitely "
            "stiff contact, i.e. the contact part of the error alone):")
        add("")
        add(T["takeup_contact"].to_markdown())
        add("")
    add("![takeup](img/accuracy_takeup.png)")
    add("")
    if not quick:
        add("## Case H: static tensions at the tangent points")
        add("")
        add("Exact: 157.645 kN (A, B) and 256.15 kN (C, D). Read from straight-line fits along the strands "
            "(`beltrs.analysis.hustrulid_tangent_tensions`).")
        add("")
        add(T["tension_A"].to_markdown(1e-3, "kN"))
        add("")
        add(T["tension_C"].to_markdown(1e-3, "kN"))
        add("")
        add("Contact stiffness at 200 elements, tension at A:")
        add("")
        add(T["tension_contact"].to_markdown(1e-3, "kN"))
        add("")
        add("![tensions](img/accuracy_tension.png)")
        add("")
        add("## Case H: axial wave speed")
        add("")
        add("400 kN·m on the upper pulley for 0.07 s from equilibrium; half-amplitude arrival over 26 m of "
            "strand (`beltrs.analysis.hustrulid_wave_speed`). Exact: √(EA/ρ) = 276.04 m/s.")
        add("")
        add(T["wave_elements"].to_markdown())
        add("")
        add(T["wave_dt"].to_markdown())
        add("")
        add("![wave](img/accuracy_wave.png)")
        add("")
        add("## Case H: counterweight-step frequency")
        add("")
        r = takeup_step_response(takeup_mass=33_600.0)
        add("Counterweight 30 000 → 33 000 kg at rest, 12 s undamped. No exact answer (the Rayleigh loop "
            f"estimate with the stepped mass is {r.frequency_loop:.4f} Hz and is itself approximate), so "
            "errors are against the Richardson reference.")
        add("")
        add(T["freq_elements"].to_markdown())
        add("")
        add(T["freq_dt"].to_markdown())
        add("")
        add("![frequency](img/accuracy_frequency.png)")
        add("")
        add("## Case K: poly-V belt drive (node model)")
        add("")
        add("Built with the node model in `benches/bench_scenes.py::kubas_drive`: r = 0.027 m, centres "
            "0.515 m, EA = 1.52e5 N (c_tra per unit strain; the per-SDE reading EA = 1216 N would give "
            "45 % creep), 0.096 kg/m, preload 550 N by initial strain (calibrated once from a stabilised "
            "trial), drive torque ramped to 15 N·m at 0.3 s, resistance 15 N·m at 8π rad/s "
            "proportional to speed, µs = 1.05, µk = 1.0 stick-force friction, contact 1e7 N/m per node, "
            f"axial damping 0.1 of critical. Run {KUBAS_DURATION} s; averages over the last "
            f"{KUBAS_WINDOW} s. T₁ − T₂ is the difference of the median span tensions; exact M/r = "
            f"{KUBAS_TORQUE / KUBAS_RADIUS:.1f} N. Slip = 1 − ω₂r/ω₁r.")
        add("")
        add(T["kubas_diff"].to_markdown())
        add("")
        add(T["kubas_slip"].to_markdown(100, "%"))
        add("")
        add("Contact stiffness at 150 elements, slip:")
        add("")
        add(T["kubas_contact"].to_markdown(100, "%"))
        add("")
        add("These tables are the node model with stick-force friction: its slip is the elastic creep "
            "(T₁ − T₂)/EA ≈ 0.37 %. The paper's creep-rate friction and nonlinear contact law "
            "N = c₁p² + c₂p + δ(p)bṗ are in the engine for both formulations (docs/kubas.md): case K "
            "with them is `tests/test_case_k_creep.py` and the integrator comparison at the end of this "
            "page; docs/kubas.md explains the slip against the paper's ≈ 1.5 %.")
        add("")
        add("![kubas](img/accuracy_kubas.png)")
        add("")
        add("## Case G: peak start-up tension")
        add("")
        add(f"Guo & Wang's conveyor (`beltrs.scenes.guo_wang_conveyor`, every assumption listed there) "
            f"shortened to {G_LENGTH:g} m so that the finest setting costs minutes, not hours; Harrison start "
            "to 2 m/s in 10 s by the speed-controlled drive; the tight-side tension is read 10 m before the "
            f"head drum every {G_INTERVAL * 1e3:g} ms over {G_DURATION:g} s. The quantity is the peak of that "
            f"signal below {G_CUTOFF:g} Hz (`beltrs.analysis.low_pass`): a belt of straight elements landing "
            "on a drum moves with a speed ripple of 1 − cos(θ/2) at the node-passing frequency v/l (10 Hz "
            "at 2 m/s with 0.2 m elements, θ = 30°), an artefact of the node model that the raw peak "
            "carries and that fades as the elements shrink "
            "(raw peaks below the tables). The full-length study with all curves is docs/case-g.md."
            + (' Wrap contact (`belt.pulley_contact = "wrap"`, [wrap-contact.md](wrap-contact.md)) removes the '
              'mechanism (the strand leaving the drum along a chord instead of the tangent): raw peaks within '
              '3 % of the low-passed ones at the default 30° (case G 150 m: +1.7 %; 300 m conveyor: +2.8 %), '
              "and case H's takeup displacement within 0.03 mm of the exact answer at 89 elements. The tables "
              'here are with nodal contact (the study sets it; the builder gives wrap contact).'))
        add("")
        add(T["g_elements"].to_markdown(1e-3, "kN"))
        add("")
        add(T["g_dt"].to_markdown(1e-3, "kN"))
        add("")
        raw = ", ".join(f"{n} nodes / dt {dt * 1e6:.1f} µs: {v / 1e3:.1f} kN" for (n, dt), v in sorted(G_RAW.items()))
        add(f"Raw peaks (with the chordal ripple): {raw}.")
        add("")
        add("![case G](img/accuracy_case_g.png)")
        add("")
        L.extend(integrator_section(T))
        add("")
        add(conclusions(T))
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("\n".join(L) + "\n", encoding="utf-8")


def conclusions(T: dict[str, study.StudyTable]) -> str:
    te = T["takeup_elements"]
    tc = T["takeup_contact"]
    we = T["wave_elements"]
    wd = T["wave_dt"]
    fe = T["freq_elements"]
    kd = T["kubas_diff"]
    ks = T["kubas_slip"]
    lines = [
        "## Conclusions",
        "",
        "**Measured orders.**",
        f"- Takeup displacement against element count: {order_range(te)} (second order, the chord polygon).",
        f"- Tangent-point tensions: the error does not fall with the mesh (orders {order_range(T['tension_A'])}); "
        f"it levels off at {T['tension_A'].error[-1] / 1e3:.3f} kN "
        f"({T['tension_A'].error[-1] / T['tension_A'].reference * 100:.2f} %) "
        "for A and C. It is neither mesh nor contact error (the contact ladder moves A by 3 N, "
        "the mesh "
        "ladder converges to 157.747 kN); the cause of this 0.06 % offset between the discrete model "
        "read-out and the continuum answer is not identified yet. It is far below the 1 % the "
        "reference allows.",
        f"- Wave speed: {', '.join(f'{v:.1f}' for v in we.value)} m/s at "
        f"{'/'.join(str(int(x)) for x in we.setting)} elements (exact 276.04): within "
        f"{np.max(we.error / we.reference) * 100:.1f} % but not converging monotonically (orders "
        f"{order_range(we)}), and the time step changes it by "
        f"{np.ptp(wd.value[1:]) / wd.reference * 100:.2f} % between fractions 0.5 and 0.125. The "
        "half-amplitude read-out of the front is the limit: the lumped chain is dispersive and the "
        "front's shape depends on the stick-slip at the driven pulley, which changes with the mesh. "
        "A read-out that converges (cross-correlation of the two signals) is next work.",
        f"- Counterweight-step frequency: {fe.value[0]:.5f} / {fe.value[1]:.5f} / {fe.value[2]:.5f} Hz at "
        "100/200/400 elements: the changes are not monotone, so no order and no Richardson reference "
        "(errors above are against the finest value). The differences (< 0.3 %) are at the "
        "resolution of the zero-crossing read-out (5 ms samples, about 3 periods); the time step "
        "changes it by less than 0.05 %.",
        f"- Case K T₁ − T₂: {kd.value[1]:.1f} N at 150 elements against M/r = {kd.reference:.1f} N "
        f"({kd.error[1] / kd.reference * 100:.2f} %), order {order_range(kd)} (the error of T₁ − T₂ "
        "comes from the chord polygon on the small pulleys, as the takeup displacement's); slip "
        f"{ks.value[1] * 100:.3f} % at 150 elements (the elastic creep (T₁ − T₂)/EA = "
        f"{kd.reference / 1.52e5 * 100:.3f} %), not monotone in the mesh at the 0.005 % level.",
        "",
        "- Case G peak start-up tension (200 m, below 2 Hz): "
        f"{', '.join(f'{v / 1e3:.1f}' for v in T['g_elements'].value)} kN at 0.2/0.1/0.05 m elements "
        f"and {', '.join(f'{v / 1e3:.1f}' for v in T['g_dt'].value)} kN at time-step fractions 0.8/0.4/0.2: "
        "within 1 % of each other and not monotone, so no order: the engineering figure is converged at the "
        "default 0.2 m (30° on the drum) and fraction 0.5. The raw peak is not: "
        + ", ".join(f"{v / 1e3:.1f}" for (n, dt), v in sorted(G_RAW.items()) if n > 0 and dt in
                    {r.time_step for r in T['g_elements'].rows})
        + " kN at the three meshes, the chordal ripple fading with the element angle; reading a raw peak "
        "within 5 % of the smooth one takes elements of about 7° of arc on the drive drum.",
        "",
        "**Where contact stiffness stops mattering.** Penalty contact sinks each node by f/k; the answer "
        "moves as 1/k (order ≈ 1 in the compliance). For the case H takeup displacement the change from "
        f"2e7 to 2e8 N/m is {abs(tc.value[-1] - tc.value[-2]) * 1e3:.1f} mm and the contact error left at 2e8 "
        f"is {tc.error[-1] * 1e3:.2f} mm, against a 200-element mesh error of {te.error[1] * 1e3:.0f} mm: "
        "from about 2e7 N/m up (case H) the contact stiffness no longer matters "
        "next to the mesh, and stiffer contact only costs (it shrinks the stable step and, more, slows "
        "the static relaxation).",
        "",
        "**Pareto front and recommended defaults.** For static answers the only lever is the element "
        "count, and the cost per halving of the element length is about 2–5× (twice the nodes, a smaller "
        "step, more relaxation steps). For dynamic answers the time step is the cheap lever to leave alone: "
        "halving the fraction doubles the cost and moved the wave speed and the frequency by at most "
        "0.05 %, far less than the mesh. The grid of element counts × time-step fractions in the "
        "wave-speed plot has its front at 100 elements: the half-amplitude read-out "
        "does not improve with the mesh, so the coarsest mesh is as good as any for it. "
        "Recommended: **time_step_fraction 0.5–0.9** (0.5 is the "
        "default and keeps a margin for contact and friction transients; 0.9 is safe for smooth runs), "
        "**elements of at most 30° of arc on the smallest pulley** (the default) for tensions, wave "
        "speeds and frequencies (errors below 1.5 %), and 2–4× that count when the takeup displacement "
        "matters (5 % → 0.3 %); contact stiffness such that the largest nodal force sinks a node "
        "by under about 1 mm (case H default 2e8 N/m: 0.13 MN sinks 0.65 mm).",
    ]
    return "\n".join(lines)


if __name__ == "__main__":
    main()
