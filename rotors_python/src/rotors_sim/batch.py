"""Many independent worlds in one process, stepped in parallel on threads (one call steps all)."""

from __future__ import annotations

from collections.abc import Callable, Sequence

from rotors_sim import _engine
from rotors_sim.world import World


class Batch:
    """Worlds made by `make(index)`; `step(n)` advances every one n steps on `threads` threads
    (0: one per core) with the GIL released."""

    def __init__(self, make: Callable[[int], World], count: int, threads: int = 0):
        self.worlds: list[World] = [make(i) for i in range(count)]
        self.threads = threads
        self._engines = [w.engine for w in self.worlds]

    def __len__(self) -> int:
        return len(self.worlds)

    def __getitem__(self, i: int) -> World:
        return self.worlds[i]

    def step(self, n: int = 1, only: Sequence[int] | None = None) -> None:
        engines = self._engines if only is None else [self._engines[i] for i in only]
        _engine.step_all(engines, int(n), self.threads)
