"""Tables, labelled arrays, JSON-ready dicts and HTML for thud's results.

The result classes are native (``thud._thud``); their ``impacts_frame``, ``history_frame``,
``to_dataframe``, ``to_xarray``, ``as_dict(json=True)`` and ``_repr_html_`` methods call the
functions here. Every column is taken from the result's own arrays by key (the keys of the
command line's JSON records, units in the names), so a field added to a record shows up in
the tables without a change here. pandas and xarray are optional: a method that needs one
raises ImportError saying what to install.
"""

from __future__ import annotations

import html
import json
import math
from typing import Any, Dict, List, Tuple

import numpy as np

#: Unit of a column from its name's suffix (longest first), for xarray attrs and HTML.
_UNITS: List[Tuple[str, str]] = [
    ("_m_s2", "m/s²"),
    ("_cm_s", "cm/s"),
    ("_m_s", "m/s"),
    ("_pa_s_m", "Pa·s/m"),
    ("_n_s_m", "N·s/m"),
    ("_n_m", "N/m"),
    ("_kg", "kg"),
    ("_db", "dB"),
    ("_hz", "Hz"),
    ("_pa", "Pa"),
    ("_deg", "degrees"),
    ("_j", "J"),
    ("_n", "N"),
    ("_s", "s"),
    ("_m", "m"),
]


def unit_of(name: str) -> str:
    """The unit a column's name states ("spl_max_db" → "dB"), or "" when it states none."""
    for suffix, unit in _UNITS:
        if name.endswith(suffix):
            return unit
    return ""


def _need(module: str, what: str) -> Any:
    try:
        return __import__(module)
    except ImportError as e:
        raise ImportError(
            f"{what} needs {module}, which is not installed: pip install {module} "
            f"(or pip install 'thud-damper[frames]' for pandas and xarray)"
        ) from e


def jsonable(value: Any) -> Any:
    """`value` with every NumPy array as (nested) lists, every NumPy scalar as a Python number
    and every NaN as None: what `json.dumps` writes as standard JSON."""
    if isinstance(value, dict):
        return {str(k): jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [jsonable(v) for v in value]
    if isinstance(value, np.ndarray):
        return jsonable(value.tolist())
    if isinstance(value, np.generic):
        return jsonable(value.item())
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def _first(columns: Dict[str, Any], *lead: str) -> Dict[str, Any]:
    """`columns` with the keys `lead` (those present) first, the others in their order."""
    out = {k: columns[k] for k in lead if k in columns}
    out.update((k, v) for k, v in columns.items() if k not in out)
    return out


def _frame(columns: Dict[str, Any], attrs: Dict[str, Any], what: str) -> Any:
    pd = _need("pandas", what)
    df = pd.DataFrame(columns)
    df.attrs.update(attrs)
    return df


def pulse_frame(p: Any) -> Any:
    """Pulse.to_dataframe(): the waveform, t_s (s) and p_pa (Pa); the scalars in .attrs."""
    d = p.as_dict()
    scalars = {k: v for k, v in d.items() if not isinstance(v, (np.ndarray, dict))}
    return _frame({"t_s": p.t_s, "p_pa": p.p_pa}, scalars, "Pulse.to_dataframe()")


def impacts_frame(run: Any) -> Any:
    """Run.impacts_frame(): one row per impact, t_s first, the record's columns in order."""
    return _frame(_first(dict(run.impacts), "t_s"), {"design": run.design}, "Run.impacts_frame()")


def history_frame(run: Any) -> Any:
    """Run.history_frame(): the uniform time history, t_s first."""
    return _frame(_first(dict(run.history), "t_s"), {"design": run.design}, "Run.history_frame()")


def ensemble_frame(e: Any) -> Any:
    """Ensemble.to_dataframe(): one row per run k, ball_position_m first."""
    cols = _first(dict(e.ensemble), "ball_position_m")
    n = len(next(iter(cols.values()))) if cols else 0
    attrs = {"design": e.design, "runs": e.runs, "zone": e.zone, "zone3_probability": e.zone3_probability,
             "agreement": e.agreement}
    return _frame({"run": np.arange(n), **cols}, attrs, "Ensemble.to_dataframe()")


def _grids(d: Dict[str, Any], shape: Tuple[int, ...]) -> Dict[str, np.ndarray]:
    """The arrays of `d` of exactly `shape`, by key."""
    return {k: v for k, v in d.items() if isinstance(v, np.ndarray) and v.shape == shape}


def chart_frame(c: Any) -> Any:
    """Chart.to_dataframe(): tidy, one row per cell (gap_m, mass_kg, metrics); with an ensemble
    one row per run of each cell (gap_m, mass_kg, run, the run's metrics, then the cell's
    medians as median_*, zone3_probability and agreement)."""
    d = c.as_dict()
    gaps, masses = np.asarray(c.gaps_m), np.asarray(c.masses_kg)
    shape = (len(gaps), len(masses))
    cells = _grids(d, shape)
    attrs = {"design": c.design, "thresholds": c.thresholds, "runs": c.runs}
    g, m = np.meshgrid(gaps, masses, indexing="ij")
    if not c.runs or c.runs <= 1 or c.ensemble is None:
        cols = {"gap_m": g.ravel(), "mass_kg": m.ravel()}
        cols.update((k, v.ravel()) for k, v in cells.items())
        return _frame(cols, attrs, "Chart.to_dataframe()")
    n = c.runs
    runs = _first(_grids(c.ensemble, shape + (n,)), "ball_position_m")
    cols = {
        "gap_m": np.repeat(g.ravel(), n),
        "mass_kg": np.repeat(m.ravel(), n),
        "run": np.tile(np.arange(n), g.size),
    }
    cols.update((k, v.reshape(-1)) for k, v in runs.items())
    for k, v in cells.items():
        name = k if k in ("zone3_probability", "agreement") else f"median_{k}"
        cols[name] = np.repeat(v.ravel(), n)
    return _frame(cols, attrs, "Chart.to_dataframe()")


def _flat_spread(spread: Dict[str, Any]) -> Dict[str, Any]:
    """{metric: {"p10", "median", "p90"}} as {metric_p10: …, metric_median: …, …}."""
    out: Dict[str, Any] = {}
    for metric, stats in spread.items():
        if isinstance(stats, dict):
            for stat, v in _first(stats, "p10", "median", "p90").items():
                out[f"{metric}_{stat}"] = v
    return out


def chart_xarray(c: Any) -> Any:
    """Chart.to_xarray(): a Dataset on gap_m × mass_kg (× run with an ensemble)."""
    xr = _need("xarray", "Chart.to_xarray()")
    d = c.as_dict()
    gaps, masses = np.asarray(c.gaps_m), np.asarray(c.masses_kg)
    shape = (len(gaps), len(masses))
    dims = ("gap_m", "mass_kg")
    coords: Dict[str, Any] = {
        "gap_m": ("gap_m", gaps, {"units": "m", "long_name": "gap d"}),
        "mass_kg": ("mass_kg", masses, {"units": "kg", "long_name": "impact mass m"}),
    }
    data: Dict[str, Any] = {}
    for k, v in _grids(d, shape).items():
        data[k] = (dims, v, {"units": unit_of(k)})
    if c.spread is not None:
        for k, v in _flat_spread(c.spread).items():
            data[k] = (dims, v, {"units": unit_of(k.rsplit("_", 1)[0])})
    if c.ensemble is not None and c.runs > 1:
        coords["run"] = ("run", np.arange(c.runs), {"long_name": "run k (ball offset)"})
        for k, v in _grids(c.ensemble, shape + (c.runs,)).items():
            data[f"run_{k}"] = (dims + ("run",), v, {"units": unit_of(k)})
    attrs = {"runs": c.runs, "thresholds": json.dumps(jsonable(c.thresholds)),
             "design": json.dumps(jsonable(c.design))}
    return xr.Dataset(data, coords=coords, attrs=attrs)


def response_frame(r: Any) -> Any:
    """Response.to_dataframe(): one row per frequency of each sweep (direction, freq_hz, the
    point's figures; an ensemble's spread as {figure}_p10 / _median / _p90)."""
    rows: Dict[str, List[Any]] = {}
    parts = []
    for sweep in r.sweeps:
        cols: Dict[str, Any] = {}
        for k, v in sweep.items():
            if k == "direction" or k == "ensemble":
                continue
            if k == "spread" and isinstance(v, dict):
                cols.update(_flat_spread(v))
            elif isinstance(v, np.ndarray) and v.ndim == 1:
                cols[k] = v
        cols = _first(cols, "freq_hz")
        n = len(cols.get("freq_hz", []))
        parts.append(({"direction": [sweep["direction"]] * n, **cols}, n))
    for cols, _ in parts:
        for k in cols:
            rows.setdefault(k, [])
    for cols, n in parts:
        for k in rows:
            v = cols.get(k)
            rows[k].extend(list(v) if v is not None else [None] * n)
    attrs = {"design": r.design, "force_n": r.force_n, "runs": r.runs, "continuation": r.continuation}
    return _frame(rows, attrs, "Response.to_dataframe()")


def _cell(v: Any) -> str:
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return "—"
    if isinstance(v, float):
        return f"{v:.6g}"
    return html.escape(str(v))


def repr_html(obj: Any) -> str:
    """_repr_html_: the repr as a caption over a table of the result's scalar fields (name,
    value, unit) and, for a run or a chart, the design's mass and gap."""
    d = obj.as_dict()
    rows = []
    design = d.get("design")
    damper = design.get("damper") if isinstance(design, dict) else None
    if isinstance(damper, dict):
        for key in ("impact_mass_kg", "gap_m", "main_mass_kg", "v0_m_s"):
            if key in damper:
                rows.append((f"design: {key}", damper[key]))
    for k, v in d.items():
        if k == "design" or isinstance(v, (dict, list, np.ndarray)):
            continue
        rows.append((k, v))
    body = "".join(
        f"<tr><td style='text-align:left'>{html.escape(k)}</td><td>{_cell(v)}</td>"
        f"<td style='text-align:left'>{html.escape(unit_of(k))}</td></tr>"
        for k, v in rows
    )
    return (
        f"<table class='thud'><caption style='text-align:left'><code>{html.escape(repr(obj))}</code></caption>"
        f"<thead><tr><th>field</th><th>value</th><th>unit</th></tr></thead><tbody>{body}</tbody></table>"
    )
