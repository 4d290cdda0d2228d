"""Plots (matplotlib, imported lazily and drawn off-screen)."""

from __future__ import annotations

from pathlib import Path
from typing import Optional, Union

import numpy as np

__all__ = ["plot_tension_around_belt"]


def plot_tension_around_belt(
    node_position: np.ndarray,
    tension: np.ndarray,
    path: Union[str, Path],
    *,
    title: str = "Belt tension",
    takeup_time: Optional[np.ndarray] = None,
    takeup_travel: Optional[np.ndarray] = None,
) -> Path:
    """Write a PNG: the belt coloured by tension (kN) beside tension against node index,
    plus takeup travel against time if given. Returns the path written."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import LineCollection

    x = np.asarray(node_position)
    t = np.asarray(tension) / 1e3
    ncols = 3 if takeup_time is not None else 2
    fig, axes = plt.subplots(1, ncols, figsize=(5 * ncols, 6))
    seg = np.stack([x, np.roll(x, -1, axis=0)], axis=1)
    lc = LineCollection(seg, array=t, cmap="viridis", linewidths=4)
    ax = axes[0]
    ax.add_collection(lc)
    ax.autoscale()
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(title)
    fig.colorbar(lc, ax=ax, label="tension (kN)")
    ax = axes[1]
    ax.plot(np.arange(len(t)), t, ".-")
    ax.set_xlabel("element")
    ax.set_ylabel("tension (kN)")
    ax.grid(True)
    if takeup_time is not None and takeup_travel is not None:
        ax = axes[2]
        ax.plot(takeup_time, takeup_travel)
        ax.set_xlabel("time (s)")
        ax.set_ylabel("takeup position y (m)")
        ax.grid(True)
    fig.tight_layout()
    out = Path(path)
    fig.savefig(out, dpi=100)
    plt.close(fig)
    return out
