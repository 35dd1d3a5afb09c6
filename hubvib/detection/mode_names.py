"""One identity per mode through a crack study: numbered at the intact spectrum, followed by
MAC, split pairs named (SI).

A repeated frequency of the intact reducer (cyclic symmetry) splits when the crack breaks
the symmetry.  Its shapes at the intact state are any basis of the pair's plane, so MAC
alone may hand the lower number to either member.  Here the members of a split pair are
numbered by frequency at every depth: the lower number is the lower member, in every table,
file and figure.  Detection output names a mode with its model: :func:`rigid_label`, and
``hubvib.elastic.content.elastic_label`` (with the coupled modes' classes).
"""
from __future__ import annotations

import numpy as np

from hubvib.lumped.tracking import match

#: intact frequencies closer than this (relative) form one repeated group
REPEATED = 1e-6


def repeated_groups(omega0) -> list[list[int]]:
    """Groups (0-based mode indices, ascending) of intact frequencies ``omega0`` that are
    repeated; single modes form groups of one."""
    omega0 = np.asarray(omega0, dtype=float)
    order = np.argsort(omega0, kind="stable")
    groups: list[list[int]] = []
    for i in order:
        if groups and abs(omega0[i] - omega0[groups[-1][-1]]) <= REPEATED * abs(omega0[i]):
            groups[-1].append(int(i))
        else:
            groups.append([int(i)])
    return [sorted(g) for g in groups]


def tracked_order(spectra) -> np.ndarray:
    """(depths, modes): ``order[k, i]`` is the index in ``spectra[k]`` of mode i (numbered
    in ``spectra[0]``), followed by MAC from depth to depth, the members of each repeated
    intact group ordered by frequency at every depth."""
    n = spectra[0].omega.size
    order = np.empty((len(spectra), n), dtype=int)
    order[0] = np.arange(n)
    for k in range(1, len(spectra)):
        step, _ = match(spectra[k - 1], spectra[k])
        order[k] = step[order[k - 1]]
    for group in repeated_groups(spectra[0].omega):
        if len(group) < 2:
            continue
        for k, spectrum in enumerate(spectra):
            members = order[k, group]
            order[k, group] = members[np.argsort(spectrum.omega[members], kind="stable")]
    return order


def tracked(values: np.ndarray, order: np.ndarray) -> np.ndarray:
    """``values`` (depths, modes) per spectrum index, rearranged to the tracked modes."""
    return np.take_along_axis(np.asarray(values), order, axis=1)


def mode_names(omega0) -> list[str]:
    """Per mode the name every table and figure uses: ``"7"``, or for a repeated intact
    frequency that splits ``"7 (split pair 7/8, lower)"``."""
    names = [str(i + 1) for i in range(len(omega0))]
    for group in repeated_groups(omega0):
        if len(group) < 2:
            continue
        numbers = "/".join(str(i + 1) for i in group)
        if len(group) == 2:
            for i, which in zip(group, ("lower", "upper")):
                names[i] = f"{i + 1} (split pair {numbers}, {which})"
        else:
            for rank, i in enumerate(group, 1):
                names[i] = f"{i + 1} (split group {numbers}, {rank} of {len(group)})"
    return names


def rigid_curve_label(name: str, frequency_hz: float, kind: str) -> str:
    """A rigid-ring mode in a figure's legend or row:
    ``rigid 13 (split pair 13/14, lower): 4548.5 Hz translational`` (``name`` from
    :func:`mode_names`, ``frequency_hz`` its intact frequency)."""
    return f"rigid {name}: {frequency_hz:.1f} Hz {kind}"


def rigid_label(i: int, kind: str, frequency_hz: float) -> str:
    """``rigid 13 (rotational, 4548.5 Hz)``: mode ``i`` (0-based) of the 9 + 3N model."""
    return f"rigid {i + 1} ({kind}, {frequency_hz:.1f} Hz)"
