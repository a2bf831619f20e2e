"""The Python layer of ``thud``'s functions: explicit keyword signatures built from the
engine's parameter table (``thud._thud._parameters()``), and ``progress=True`` as a bar."""

from __future__ import annotations

import inspect
import os
import sys
from typing import Any, Callable, Dict, List, Literal, Optional, Sequence, Union

from . import _thud

class Bar:
    """``progress=True``: tqdm's bar when tqdm is installed, else one line on stderr redrawn
    in place ("sweep: 120/400 (30 %)") and ended at the last item."""

    def __init__(self, what: str) -> None:
        self.what = what
        self.tqdm: Any = None
        self.shown = 0

    def __call__(self, done: int, total: int) -> None:
        if self.tqdm is None:
            try:
                from tqdm.auto import tqdm
            except ImportError:
                tqdm = None
            if tqdm is not None:
                self.tqdm = tqdm(total=total, desc=self.what)
        if self.tqdm is not None:
            self.tqdm.update(done - self.shown)
            if done >= total:
                self.tqdm.close()
        else:
            pct = 100 * done // max(total, 1)
            end = "\n" if done >= total else ""
            sys.stderr.write(f"\r{self.what}: {done}/{total} ({pct} %){end}")
            sys.stderr.flush()
        self.shown = done


def with_progress(params: Dict[str, Any], what: str) -> Dict[str, Any]:
    """``progress=True`` as a bar; a callable or None/False as given."""
    if params.get("progress") is True:
        params["progress"] = Bar(what)
    return params


#: A number in the parameter's plain unit, or a string with a unit ("40.5g").
Quantity = Union[float, str]
#: A whole number (or its text, "1e4").
Count = Union[int, str]
#: progress=: True for a bar, or a callable progress(done, total).
ProgressArg = Union[bool, Callable[[int, int], object], None]

#: The annotation of an option keyword (the run options each function takes itself).
_OPTION_TYPES: Dict[str, Any] = {
    "preset": Optional[str],
    "design": Union[str, "os.PathLike[str]", None],
    "period": Optional[Count],
    "symmetric": bool,
    "guess": Optional[Sequence[Quantity]],
    "points": Count,
    "samples": Count,
    "ensemble": Count,
    "continuation": bool,
    "progress": ProgressArg,
    "no_limit": bool,
    "quantity": Literal["x", "v", "a"],
    "transient": Count,
    "branches": Optional[Count],
}

#: The positional parameters of each function (name, annotation, default or P.empty).
_POSITIONAL: Dict[str, List[Any]] = {
    "pulse": [],
    "simulate": [],
    "simulate_ensemble": [("runs", Count, inspect.Parameter.empty)],
    # None, None with keywords given as sequences: a study over any parameters (xarray).
    "sweep": [("masses_kg", Any, None), ("gaps_m", Any, None)],
    # None: the engine's default band of the design (0.6–1.6 × its natural frequency).
    "response": [("freqs_hz", Any, None)],
    "fit_damper": [("t_s", Any, inspect.Parameter.empty), ("x", Any, inspect.Parameter.empty)],
    "bifurcation": [],
    "orbit": [],
    "continuation": [],
    "impact_map": [],
    "basins": [("grid", Count, 20), ("w0", Any, (-1.0, 1.0))],
    "restitution": [("masses_kg", Any, "5g:100g:20"), ("u0", Quantity, 1.4), ("target", Optional[Quantity], None)],
}


def _annotation(row: Dict[str, Any]) -> Any:
    """The annotation of one row of the engine's parameter table."""
    accepts = row["accepts"]
    if accepts == "quantity":
        return Optional[Quantity]
    if accepts == "choice":
        return Optional[Literal[tuple(row["choices"])]]  # type: ignore[misc]
    if accepts == "switch":
        return Optional[bool]
    if accepts == "count":
        return Optional[Count]
    return Optional[str]


def _signature(name: str, table: Dict[str, Any], returns: Any) -> inspect.Signature:
    """The signature of the function `name` from the engine's table: its positional
    parameters, then `preset`, every named parameter of the engine (table order) and the
    function's other options, all keyword-only."""
    P = inspect.Parameter
    params = [P(n, P.POSITIONAL_OR_KEYWORD, annotation=a, default=d) for n, a, d in _POSITIONAL[name]]
    options = table["options"][name]
    defaults = table["defaults"]
    rows = table["pulse" if name == "pulse" else "design"]
    refused = set(table["refused"].get(name, []))
    for first in ("preset", "design"):
        if first in options:
            params.append(P(first, P.KEYWORD_ONLY, default=None, annotation=_OPTION_TYPES[first]))
    for row in rows:
        if row["name"] not in refused:
            params.append(P(row["name"], P.KEYWORD_ONLY, default=None, annotation=_annotation(row)))
    for o in options:
        if o not in ("preset", "design"):
            params.append(P(o, P.KEYWORD_ONLY, default=defaults.get(o), annotation=_OPTION_TYPES[o]))
    return inspect.Signature(params, return_annotation=returns)


def keywords_doc(name: str, table: Dict[str, Any]) -> str:
    """The "Keywords" section of the function `name`'s docstring, generated from the engine's
    parameter table: one line per row the function takes (table order), the row's own line
    (help, range, alias) and, for a choice, its names."""
    rows = table["pulse" if name == "pulse" else "design"]
    refused = set(table["refused"].get(name, []))
    lines = ["Keywords (the engine's parameter table; None = not given):"]
    for row in rows:
        if row["name"] in refused:
            continue
        choices = " | ".join(f'"{c}"' for c in row.get("choices", []))
        lines.append(f"    {row['name']}: {row['doc']}" + (f" ({choices})" if choices else ""))
    return "\n".join(lines)


def document(namespace: Dict[str, Any]) -> None:
    """Gives each function of the package (in `namespace`) the native one's docstring, its
    keywords' documentation from the engine's table and the engine's signature."""
    table = _thud._parameters()
    returns = {"pulse": _thud.Pulse, "simulate": Union[_thud.Run, _thud.Ensemble],
               "simulate_ensemble": _thud.Ensemble, "sweep": Any, "response": _thud.Response,
               "fit_damper": "thud.DamperFit", "bifurcation": Any, "orbit": "thud.Orbit",
               "continuation": Any, "impact_map": "thud.ImpactMap", "basins": "thud.Basins",
               "restitution": "thud.Restitution"}
    for name, ret in returns.items():
        fn = namespace[name]
        native = getattr(_thud, name, None)
        doc = (native.__doc__ if native is not None else fn.__doc__) or ""
        # The native docstring opens with "name(**params) -> T": the signature says it now.
        doc = doc.split("\n\n", 1)[-1] if doc.startswith(f"{name}(") else doc
        fn.__doc__ = doc.rstrip() + "\n\n" + keywords_doc(name, table) + "\n"
        fn.__signature__ = _signature(name, table, ret)  # type: ignore[attr-defined]

