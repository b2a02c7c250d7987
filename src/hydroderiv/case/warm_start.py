"""Starting a condition from another condition's solution on the same mesh.

The new case keeps its own boundary conditions (its inflow vector, its wall functions) and takes only the
solved internal field. Solutions are written in binary, and a field of a few hundred thousand cells takes
seconds to parse and write again as text. So the field file is spliced as bytes instead: the solved file up
to the end of its ``internalField`` entry, then the new case's ``boundaryField``. The list header of the
internal field gives its exact byte length, so the splice never has to search inside binary data.
"""

from __future__ import annotations

import re
from pathlib import Path

from .._io import atomic_write_bytes
from ..errors import ConfigurationError

# Components per cell value of each field type OpenFOAM writes as a List<type>.
_COMPONENTS = {"scalar": 1, "vector": 3, "sphericalTensor": 1, "symmTensor": 6, "tensor": 9}
_NONUNIFORM = re.compile(rb"\binternalField\s+nonuniform\s+List<(\w+)>\s*(\d+)\s*\(")
_INTERNAL = re.compile(rb"^internalField\b", re.M)
_BOUNDARY = re.compile(rb"^boundaryField\b", re.M)
_LOCATION = re.compile(rb'(\blocation\s+)"[^"]*"')


def _header_entry(data: bytes, key: str) -> str | None:
    header = data[: data.find(b"}") + 1]
    found = re.search(rb"\b" + key.encode() + rb"\s+\"?([^\";]+)\"?\s*;", header)
    return found.group(1).decode() if found else None


def _scalar_bytes(data: bytes) -> int:
    """Bytes per scalar in a binary field file, from the ``arch`` header entry (double if absent)."""
    arch = _header_entry(data, "arch") or ""
    found = re.search(r"scalar=(\d+)", arch)
    return int(found.group(1)) // 8 if found else 8


def _internal_field_end(data: bytes, path: Path, n_cells: int | None) -> int:
    """Offset in ``data`` where the entry after ``internalField`` (``boundaryField``) starts."""
    start = _INTERNAL.search(data)
    if start is None:
        raise ConfigurationError(f"{path} has no internalField entry; not an OpenFOAM field file?")
    search_from = start.end()
    listed = _NONUNIFORM.match(data, start.start())
    if listed is not None:
        kind, count = listed.group(1).decode(), int(listed.group(2))
        if n_cells is not None and count != n_cells:
            raise ConfigurationError(
                f"cannot warm-start from {path}: it holds {count} cell values, the mesh has {n_cells} cells"
            )
        if _header_entry(data, "format") == "binary":
            if kind not in _COMPONENTS:
                raise ConfigurationError(f"{path}: cannot warm-start from a List<{kind}> field")
            search_from = listed.end() + count * _COMPONENTS[kind] * _scalar_bytes(data)
            if data[search_from : search_from + 1] != b")":
                raise ConfigurationError(f"{path}: the binary internalField is not {count} {kind} values long")
    boundary = _BOUNDARY.search(data, search_from)
    if boundary is None:
        raise ConfigurationError(f"{path} has no boundaryField after its internalField")
    return boundary.start()


def take_internal_field(target: Path, source: Path, n_cells: int | None = None) -> None:
    """Give the field file ``target`` the internal field of the solved field file ``source`` (same mesh).

    ``target`` keeps its boundaryField; its header, dimensions and internal field come from ``source``
    (the header carries the binary format and its word sizes), with the location set to ``target``'s time.
    ``n_cells``, if given, is checked against the length of the solved field.
    """
    target, source = Path(target), Path(source)
    solved = source.read_bytes()
    own = target.read_bytes()
    head = solved[: _internal_field_end(solved, source, n_cells)]
    head = _LOCATION.sub(rb'\g<1>"' + target.parent.name.encode() + rb'"', head, count=1)
    boundary = _BOUNDARY.search(own)
    if boundary is None:
        raise ConfigurationError(f"{target} has no boundaryField entry")
    atomic_write_bytes(target, head + own[boundary.start() :])
