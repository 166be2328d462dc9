"""What the 3-D view writes beside its masses, so a class can say "the euler ball" or "the blue row".

A scene with a few masses (up to LABELLED_MASSES: the methods of `integrators`, the regimes of
`regimes`, the two drags of `drag`) gets its label on every mass, on two short lines, following the
mass. A scene that groups many masses in rows (VIEW["rows"], `resonance`) gets one label per row,
what its masses share (`b = 0.5 kg/s`), at the row's first mass, and a label under every other
mass of the front row with what differs along it (`ω = 2 rad/s`). A single mass needs none.

Nothing here imports vpython: tests/test_mass_labels.py checks the texts for every scene.
"""
from __future__ import annotations

from dataclasses import dataclass

LABELLED_MASSES = 6   # more masses than this (and no rows): no labels, they would cover the picture


@dataclass(frozen=True)
class MassLabel:
    """A label beside mass `index`: `follows` the mass as it moves, or stays where the mass starts;
    `side` is where it sits: "above", "left" (of a row) or "below"."""
    index: int
    text: str
    follows: bool
    side: str


def mass_labels(model, view: dict) -> list[MassLabel]:
    """The labels the 3-D view draws for a model, from its masses' labels (model.labels)."""
    labels = list(model.labels)
    if len(labels) < 2:
        return []
    rows = view.get("rows")
    if rows is not None:
        return _row_labels(labels, [int(j) for j in rows(model)])
    if len(labels) > LABELLED_MASSES:
        return []
    return [MassLabel(i, two_lines(label), follows=True, side="above") for i, label in enumerate(labels)]


def two_lines(label: str) -> str:
    """`under-damped (b = 0.8 kg/s)` → `under-damped` over `b = 0.8 kg/s`; `linear, b = …` likewise."""
    if " (" in label and label.endswith(")"):
        head, tail = label[:-1].split(" (", 1)
    elif ", " in label:
        head, tail = label.split(", ", 1)
    else:
        return label
    return f"{head}\n{tail}"


def _row_labels(labels: list[str], rows: list[int]) -> list[MassLabel]:
    found = []
    members = {}
    for i, row in enumerate(rows):
        members.setdefault(row, []).append(i)
    front = members[min(members)]
    for row, indices in members.items():
        shared, _ = _split(labels, indices)
        found.append(MassLabel(indices[0], shared, follows=False, side="left"))
    _, differing = _split(labels, front)
    for n, i in enumerate(front):
        if n % 2 == 0 and differing[n]:
            found.append(MassLabel(i, differing[n].replace(" rad/s", "\nrad/s"), follows=False, side="below"))
    return found


def _split(labels: list[str], indices: list[int]) -> tuple[str, list[str]]:
    """What the labels of these masses share (whole `, `-separated parts from the start), and what
    is left of each."""
    parts = [labels[i].split(", ") for i in indices]
    n = 0
    while all(len(p) > n + 1 and p[n] == parts[0][n] for p in parts):
        n += 1
    return ", ".join(parts[0][:n]), [", ".join(p[n:]) for p in parts]
