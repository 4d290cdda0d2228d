"""Plot a two-pulley belt drive: pulley speeds and slip, span tensions, and the normal and
friction force round each pulley by wrap angle (Kubas 2014, figures 14-17).

    python examples/plot_belt_drive.py [SCENE.toml] [--out DIR] [--duration S]

SCENE defaults to examples/case_k.toml (Kubas's case K); examples/cepon_boltezar.toml is the
other belt drive here. The scene is relaxed (as its [recording] table says) and run for its
recording duration (or ``--duration``) with the contact forces recorded; the last third of
the run is taken as steady running. Writes to DIR (default: a new temporary directory,
printed) the PNGs

- ``speeds.png``: both pulleys' speeds and the slip 1 - (w2 r2)/(w1 r1);
- ``tensions.png``: the tension in the middle of each span;
- ``contact_forces.png``: normal and friction force per belt point round the drive and the
  driven pulley against the wrap angle along the direction of travel (from where the belt
  meets the pulley), averaged over the steady window (``Result.contact_profile``);
- ``belt_point.png``: one belt point followed round the drive (Kubas's figures 15-17): the
  tension of the joint ahead of it, and the normal and friction force the pulleys put on it;

and prints the steady figures. Headless (matplotlib's Agg backend).
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import beltrs  # noqa: E402


def span_tensions(res: beltrs.Result, c1: np.ndarray, c2: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``[n]`` mean tension of the elements over the middle third of each span: left and
    right of the line from pulley 1's centre to pulley 2's."""
    axis = (c2 - c1) / np.linalg.norm(c2 - c1)
    x = res.node_position
    mid = 0.5 * (x + np.roll(x, -1, axis=1)) - c1
    along = mid @ axis / np.linalg.norm(c2 - c1)
    side = mid[..., 0] * axis[1] - mid[..., 1] * axis[0]
    inner = (along > 1 / 3) & (along < 2 / 3)
    left = np.where(inner & (side < 0), res.tension, np.nan)
    right = np.where(inner & (side > 0), res.tension, np.nan)
    return np.nanmean(left, axis=1), np.nanmean(right, axis=1)


def main(argv: list[str] | None = None) -> Path:
    here = Path(__file__).resolve().parent
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scene", nargs="?", default=str(here / "case_k.toml"), help="scene file (two pulleys)")
    parser.add_argument("--out", default=None, help="directory for the PNGs (default: a new temporary one)")
    parser.add_argument("--duration", type=float, default=None, help="simulated time, s (default: the scene's)")
    args = parser.parse_args(argv)
    out = Path(args.out) if args.out else Path(tempfile.mkdtemp(prefix="beltrs-belt-drive-"))
    out.mkdir(parents=True, exist_ok=True)

    scene = beltrs.load_scene(args.scene)
    if len(scene.pulleys) != 2:
        raise SystemExit(f"{args.scene}: a two-pulley belt drive is needed, it has {len(scene.pulleys)} pulleys")
    sim = beltrs.Simulation(scene)
    rec = scene.recording
    if rec.stabilise:
        sim.stabilise(friction=rec.stabilise_friction)
    duration = rec.duration if args.duration is None else args.duration
    res = sim.run(duration, record_interval=min(1e-3, duration / 200), contact_forces=True)
    t = res.time
    steady = t >= t[0] + 2 / 3 * (t[-1] - t[0])

    # The drive is the pulley the drives deliver power to the belt through.
    power = (res.drive_power[steady]).mean(axis=0)
    i, j = (0, 1) if power[0] >= power[1] else (1, 0)
    names = [p.name for p in scene.pulleys]
    radius = np.array([p.radius for p in scene.pulleys])
    w1, w2 = np.abs(res.pulley_speed[:, i]), np.abs(res.pulley_speed[:, j])
    with np.errstate(invalid="ignore", divide="ignore"):
        slip = 1 - (w2 * radius[j]) / (w1 * radius[i])

    fig, (a, b) = plt.subplots(2, 1, sharex=True, figsize=(7, 6))
    a.plot(t, w1, label=f"drive ({names[i]})")
    a.plot(t, w2, label=f"driven ({names[j]})")
    a.set_ylabel("speed, rad/s")
    a.legend()
    moving = w1 > 0.2 * w1.max()  # the slip of a belt barely moving is noise
    b.plot(t[moving], 100 * slip[moving])
    b.set_ylabel("slip 1 - w2 r2/(w1 r1), %")
    b.set_xlabel("time, s")
    fig.suptitle(f"{Path(args.scene).stem}: pulley speeds and slip")
    fig.tight_layout()
    fig.savefig(out / "speeds.png", dpi=120)
    plt.close(fig)

    centres = res.pulley_position[0]
    left, right = span_tensions(res, centres[i], centres[j])
    fig, ax = plt.subplots(figsize=(7, 4))
    ax.plot(t, left, label="span left of drive → driven")
    ax.plot(t, right, label="span right of drive → driven")
    ax.set_xlabel("time, s")
    ax.set_ylabel("tension, N")
    ax.legend()
    ax.set_title(f"{Path(args.scene).stem}: span tensions (middle third of each span)")
    fig.tight_layout()
    fig.savefig(out / "tensions.png", dpi=120)
    plt.close(fig)

    start = float(t[steady][0])
    fig, axes = plt.subplots(1, 2, sharey=True, figsize=(10, 4))
    for ax, k, role in ((axes[0], i, "drive"), (axes[1], j, "driven")):
        prof = res.contact_profile(k, start=start, bins=max(8, int(res.contact_normal.shape[2] / 6)))
        deg = np.degrees(prof.angle)
        ax.plot(deg, prof.normal, "o-", label="normal force")
        ax.plot(deg, prof.friction, "s-", label="friction force (on the belt, along travel)")
        ax.axhline(0, color="0.6", lw=0.8)
        ax.set_xlabel("wrap angle along the direction of travel, deg")
        ax.set_title(f"{role} pulley ({names[k]})")
    axes[0].set_ylabel("force per belt point, N")
    axes[0].legend(fontsize=8)
    fig.suptitle(f"{Path(args.scene).stem}: contact forces round the pulleys, {start:.3g}-{t[-1]:.3g} s")
    fig.tight_layout()
    fig.savefig(out / "contact_forces.png", dpi=120)
    plt.close(fig)

    # One belt point followed round (Kubas's figures 15-17): the one on the middle of the
    # slack span at the start of the steady window.
    k0 = int(np.argmax(steady))
    slack_left = np.nanmean(left[steady]) < np.nanmean(right[steady])
    axis = (centres[j] - centres[i]) / np.linalg.norm(centres[j] - centres[i])
    x = res.node_position[k0] - centres[i]
    along = x @ axis / np.linalg.norm(centres[j] - centres[i])
    side = x[:, 0] * axis[1] - x[:, 1] * axis[0]
    candidates = np.flatnonzero((side < 0) == slack_left)
    point = int(candidates[np.argmin(np.abs(along[candidates] - 0.5))])
    fig, (a, b) = plt.subplots(2, 1, sharex=True, figsize=(7, 6))
    a.plot(t, res.tension[:, point % res.tension.shape[1]])
    a.set_ylabel("tension of its joint to the next point, N")
    for k, role in ((i, "drive"), (j, "driven")):
        b.plot(t, res.contact_normal[:, k, point], label=f"normal, {role}")
        b.plot(t, np.abs(res.contact_friction[:, k, point]), "--", label=f"|friction|, {role}")
    b.set_ylabel("force on the point, N")
    b.set_xlabel("time, s")
    b.legend(fontsize=8)
    fig.suptitle(f"{Path(args.scene).stem}: belt point {point} followed round")
    fig.tight_layout()
    fig.savefig(out / "belt_point.png", dpi=120)
    plt.close(fig)

    tight, slack = sorted((np.nanmean(left[steady]), np.nanmean(right[steady])), reverse=True)
    print(f"{args.scene}: {len(res)} samples, {res.wall_time:.1f} s wall; steady window {start:.3g}-{t[-1]:.3g} s")
    print(f"  drive {w1[steady].mean():.4f} rad/s, driven {w2[steady].mean():.4f} rad/s, "
          f"slip {100 * np.nanmean(slip[steady]):.3f} %")
    print(f"  tight span {tight:.1f} N, slack span {slack:.1f} N, difference {tight - slack:.1f} N")
    print(f"  PNGs in {out}")
    return out


if __name__ == "__main__":
    main()
