# SPDX-License-Identifier: MIT
"""The records the tables pass each other: what an accuracy run is planned as, what it gave, and
a row where an engine steps faster than the subject."""
from dataclasses import dataclass
from typing import Optional


@dataclass(frozen=True)
class AccuracyStep:
    """One results row's accuracy run, before it runs: the chainbench command line, where its JSON
    goes, and the steps it was cut to (None: the scene's own)."""
    family: str
    size: str
    args: list
    path: str
    steps: Optional[int]

    @property
    def group(self):
        """The row it stands for: (family, size)."""
        return (self.family, self.size)


@dataclass(frozen=True)
class AccuracyRun:
    """What an accuracy run gave: its chainbench.run/1 JSON and the steps it ran (None: the
    scene's own)."""
    run: dict
    steps: Optional[int]


@dataclass(frozen=True, order=True)
class Loss:
    """A row where `engine` steps `faster` times faster than the subject (like against like);
    ordered by how much, then by name."""
    faster: float
    engine: str
    family: str
    size: str
