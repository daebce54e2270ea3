"""The progress bar of simulated time (tqdm, on standard error)."""

from __future__ import annotations

from tqdm import tqdm


class SimulatedTimeBar:
    """A bar from 0 to ``total`` simulated seconds of the whole head.

    Each of ``groups`` solves advances it by its own simulated seconds divided by the
    number of groups. The reports add up to the total only within round-off, so the bar is
    never moved past its end (past it tqdm warns).
    """

    def __init__(self, total: float, groups: int, description: str, enabled: bool = True,
                 unit: str = "s simulated"):
        self.share = 1.0 / groups
        self.bar = tqdm(total=round(total, 2), disable=not enabled, desc=description,
                        bar_format="{l_bar}{bar}| {n:.2f}/{total:.2f} " + unit +
                                   " [{elapsed}<{remaining}{postfix}]")

    def note(self, text: str) -> None:
        """Show ``text`` after the times (e.g. how many runs of a sweep are done)."""
        self.bar.set_postfix_str(text)

    def advance(self, seconds: float) -> None:
        """One group solved ``seconds`` more."""
        step = seconds * self.share
        self.bar.update(max(0.0, min(step, self.bar.total - self.bar.n)))

    def close(self) -> None:
        self.bar.close()
