"""Writing OpenFOAM dictionaries through foamlib (typed values in, standard OpenFOAM syntax out)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from foamlib import DimensionSet, FoamFile


def _token(word: str) -> Any:
    for kind in (int, float):
        try:
            return kind(word)
        except ValueError:
            pass
    return word


def _normalise(value: Any) -> Any:
    """Let entries be written as OpenFOAM text: 'Gauss linear' -> ('Gauss', 'linear'), dimensions -> DimensionSet.

    foamlib wants one token per string, so a multi-word entry becomes a tuple of tokens.
    """
    if isinstance(value, dict):
        return {k: _normalise(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_normalise(v) for v in value]
    if isinstance(value, str) and value.startswith("[") and value.endswith("]"):
        return DimensionSet(*(float(x) for x in value[1:-1].split()))
    if isinstance(value, str) and len(value.split()) > 1 and not value.startswith('"'):
        return tuple(_token(w) for w in value.split())
    return value


def write_foam_dict(path: str | Path, content: dict[str, Any], foam_class: str = "dictionary") -> Path:
    """Write ``content`` as an OpenFOAM dictionary file with a proper FoamFile header.

    Quoted strings must carry their quotes (``'"body.eMesh"'``); everything else is written as foamlib
    formats it (lists as ``( ... )``, booleans as yes/no, nested dicts as sub-dictionaries).
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.tmp")
    tmp.unlink(missing_ok=True)
    with FoamFile(tmp) as f:
        f["FoamFile"] = {"version": 2.0, "format": "ascii", "class": foam_class, "object": path.name}
        for key, value in content.items():
            f[key] = _normalise(value)
    tmp.replace(path)
    return path


def quoted(text: str) -> str:
    return f'"{text}"'


def write_decomposition(case: str | Path, n_procs: int) -> Path:
    """system/decomposeParDict for ``n_procs`` slabs along x. Hierarchical because scotch and metis may be
    stubs in a packaged OpenFOAM (Debian's is)."""
    return write_foam_dict(
        Path(case) / "system/decomposeParDict",
        {"numberOfSubdomains": n_procs, "method": "hierarchical", "coeffs": {"n": [n_procs, 1, 1], "order": "xyz"}},
    )
