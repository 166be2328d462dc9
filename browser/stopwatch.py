"""A stopwatch on simulated time: what a student times on the page is the model's own clock.

Wall time would be wrong on the page: the run pauses, steps one Δt at a time and runs at ¼× to 4×
(browser/clock.py), so the stopwatch reads the run's t instead. It is told t at each press and
each frame, so it keeps counting correctly through Pause (t stands still), Step (t moves one Δt)
and any speed:

    reading = held + (t − started)   while running, else held

Lap notes the reading at that moment (its time since the last lap, as a lab stopwatch does), and
Clear sets it back to 0. When the run itself restarts from t = 0 (Reset, a new constant), a
running stopwatch keeps what it has and goes on from the new t = 0.

Nothing here imports vpython: tests/test_measure_parts.py drives it with plain numbers.
"""
from __future__ import annotations


class Stopwatch:
    """Start/stop, lap and clear, on simulated time, s."""

    def __init__(self):
        self.clear()

    def clear(self) -> None:
        self.running = False
        self.held = 0.0          # s counted before the present start
        self.started = 0.0       # the run's t at the present start, s
        self.laps: list[float] = []   # the reading at each lap, s

    def start_stop(self, t: float) -> None:
        """Start counting from the run's time t, or stop and hold the reading."""
        if self.running:
            self.held = self.reading(t)
        else:
            self.started = float(t)
        self.running = not self.running

    def lap(self, t: float) -> None:
        """Note the reading now (only while running; a stopped watch has nothing to lap)."""
        if self.running:
            self.laps.append(self.reading(t))

    def run_restarted(self, t_before: float) -> None:
        """The run went back to t = 0 from t_before: keep what was counted, count on from 0."""
        if self.running:
            self.held = self.reading(t_before)
            self.started = 0.0

    def reading(self, t: float) -> float:
        """The time shown, s, with the run at t."""
        return self.held + (float(t) - self.started if self.running else 0.0)

    def lap_times(self) -> list[float]:
        """Each lap's own time: from the start, or from the lap before, s."""
        return [b - a for a, b in zip([0.0] + self.laps, self.laps)]
