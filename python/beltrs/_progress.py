"""Progress bars for long runs: tqdm when it is installed, else a small built-in one."""

from __future__ import annotations

import sys
import time
from typing import Any, Optional, TextIO


class _NoBar:
    """A progress bar that shows nothing."""

    def update(self, steps: int, sim_time: float) -> None:
        pass

    def close(self) -> None:
        pass


class _TextBar:
    """One line on stderr, redrawn at most ten times a second."""

    def __init__(self, total: int, t_end: Optional[float], stream: TextIO) -> None:
        self.total = max(int(total), 1)
        self.t_end = t_end
        self.stream = stream
        self.start = time.perf_counter()
        self.last_draw = -1.0
        self.done = 0
        self.sim_time = 0.0

    def update(self, steps: int, sim_time: float) -> None:
        self.done += int(steps)
        self.sim_time = sim_time
        now = time.perf_counter()
        if now - self.last_draw >= 0.1 or self.done >= self.total:
            self.last_draw = now
            self._draw(now)

    def _draw(self, now: float) -> None:
        frac = min(self.done / self.total, 1.0)
        width = 24
        filled = int(round(frac * width))
        elapsed = now - self.start
        rate = self.done / elapsed if elapsed > 0 else 0.0
        eta = (self.total - self.done) / rate if rate > 0 else float("nan")
        if self.t_end is None:  # a relaxation: the total is its step budget, not its length
            where = f"relaxing, step {self.done:,} of at most {self.total:,}"
            left = f"at most {eta:.0f} s left"
        else:
            where = f"t = {self.sim_time:.4g}/{self.t_end:.4g} s"
            left = f"ETA {eta:.0f} s"
        self.stream.write(
            f"\rbeltrs {100 * frac:5.1f}% |{'#' * filled}{' ' * (width - filled)}| "
            f"{where}, {rate:,.0f} steps/s, {left} "
        )
        self.stream.flush()

    def close(self) -> None:
        self._draw(time.perf_counter())
        self.stream.write("\n")
        self.stream.flush()


class _TqdmBar:
    def __init__(self, tqdm: Any, total: int, t_end: Optional[float]) -> None:
        desc = "beltrs" if t_end is not None else "beltrs relaxing (step budget)"
        self.bar = tqdm(total=int(total), unit="step", unit_scale=True, desc=desc, leave=True)
        self.t_end = t_end

    def update(self, steps: int, sim_time: float) -> None:
        if self.t_end is not None:
            self.bar.set_postfix_str(f"t = {sim_time:.4g}/{self.t_end:.4g} s", refresh=False)
        self.bar.update(int(steps))

    def close(self) -> None:
        self.bar.close()


def make_bar(progress: Optional[bool], total: int, t_end: Optional[float]) -> Any:
    """The bar to use: ``progress`` True/False forces it on/off; None shows it only when
    stderr is a terminal. tqdm is used if it can be imported. ``total`` steps; ``t_end`` the
    run's end time, s, or None for a relaxation (no time to show; ``total`` is its budget)."""
    if progress is None:
        progress = bool(getattr(sys.stderr, "isatty", lambda: False)())
    if not progress:
        return _NoBar()
    try:
        from tqdm.auto import tqdm
    except ImportError:
        return _TextBar(total, t_end, sys.stderr)
    return _TqdmBar(tqdm, total, t_end)
