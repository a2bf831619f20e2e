"""Tables, labelled arrays, JSON-ready dicts and HTML for thud's results.

The result classes are native (``thud._thud``); their ``impacts_frame``, ``history_frame``,
``to_dataframe``, ``runs_frame``, ``to_xarray``, ``as_dict(json=True)`` and ``_repr_html_``
methods call the functions here. Every DataFrame has the columns of one table of the one data
schema (``thud.schema()``, the engine's ``thud_core::schema``), in its order: the columns of the
command line's CSV file of the same result. Each column is taken from the result's own arrays
by key (the keys of the command line's JSON records, units in the names). pandas and xarray
are optional: a method that needs one raises ImportError saying what to install.
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


def schema_names(table: str) -> List[str]:
    """The column names of the schema's `table` (``thud.schema()[table]``), in order."""
    from . import _thud

    return [c[0] for c in _thud.schema()[table]]


def _table(table: str, sources: Dict[str, Any]) -> Dict[str, Any]:
    """The columns of the schema's `table`, in order, each taken from `sources` by name."""
    out: Dict[str, Any] = {}
    for name in schema_names(table):
        if name not in sources:
            raise KeyError(f"the result has no {name!r}, a column of the schema's {table!r} table")
        out[name] = sources[name]
    return out


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
    return _frame(_table("pulse", {"t_s": p.t_s, "p_pa": p.p_pa}), scalars, "Pulse.to_dataframe()")


def impacts_frame(run: Any) -> Any:
    """Run.impacts_frame(): one row per impact, the schema's `impacts` columns."""
    return _frame(_table("impacts", dict(run.impacts)), {"design": run.design}, "Run.impacts_frame()")


def history_frame(run: Any) -> Any:
    """Run.history_frame(): the uniform time history, the schema's `history` columns."""
    return _frame(_table("history", dict(run.history)), {"design": run.design}, "Run.history_frame()")


def ensemble_frame(e: Any) -> Any:
    """Ensemble.to_dataframe(): one row per run k (the index, named "run"), the schema's
    `ensemble` columns (ball_position_m, then the run's metrics)."""
    attrs = {"design": e.design, "runs": e.runs, "zone": e.zone, "zone3_probability": e.zone3_probability,
             "agreement": e.agreement}
    df = _frame(_table("ensemble", dict(e.ensemble)), attrs, "Ensemble.to_dataframe()")
    df.index.name = "run"
    return df


def _grids(d: Dict[str, Any], shape: Tuple[int, ...]) -> Dict[str, np.ndarray]:
    """The arrays of `d` of exactly `shape`, by key."""
    return {k: v for k, v in d.items() if isinstance(v, np.ndarray) and v.shape == shape}


def chart_frame(c: Any) -> Any:
    """Chart.to_dataframe(): tidy, one row per cell (gap outer, mass inner, as `thud sweep
    --csv`): the schema's `sweep` columns (mass_kg, gap_m, the metrics); with an ensemble its
    `sweep_ensemble` columns (mass_kg, gap_m, runs, the medians as metrics, X_p10 / X_median /
    X_p90 of e, e_fit, U0max and SPLmax, zone3_probability, agreement)."""
    d = c.as_dict()
    gaps, masses = np.asarray(c.gaps_m), np.asarray(c.masses_kg)
    shape = (len(gaps), len(masses))
    g, m = np.meshgrid(gaps, masses, indexing="ij")
    sources: Dict[str, Any] = {k: v.ravel() for k, v in _grids(d, shape).items()}
    sources.update(gap_m=g.ravel(), mass_kg=m.ravel())
    attrs = {"design": c.design, "thresholds": c.thresholds, "runs": c.runs}
    if not c.runs or c.runs <= 1 or c.ensemble is None:
        return _frame(_table("sweep", sources), attrs, "Chart.to_dataframe()")
    sources["runs"] = np.full(g.size, c.runs, dtype=np.int64)
    sources.update((k, np.asarray(v).ravel()) for k, v in _flat_spread(c.spread or {}).items())
    return _frame(_table("sweep_ensemble", sources), attrs, "Chart.to_dataframe()")


def chart_runs_frame(c: Any) -> Any:
    """Chart.runs_frame(): one row per run of each cell of an ensemble chart: the columns of a
    CSV part of `thud sweep --shard` but its `index` and `truncated` (run, mass_kg, gap_m,
    ball_position_m, the run's metrics)."""
    if not c.runs or c.runs <= 1 or c.ensemble is None:
        raise ValueError("Chart.runs_frame() needs a chart of ensembles (sweep(…, ensemble=N) with N > 1)")
    gaps, masses = np.asarray(c.gaps_m), np.asarray(c.masses_kg)
    shape, n = (len(gaps), len(masses)), c.runs
    g, m = np.meshgrid(gaps, masses, indexing="ij")
    sources: Dict[str, Any] = {k: v.reshape(-1) for k, v in _grids(c.ensemble, shape + (n,)).items()}
    sources.update(gap_m=np.repeat(g.ravel(), n), mass_kg=np.repeat(m.ravel(), n), run=np.tile(np.arange(n), g.size))
    names = [k for k in schema_names("shard_part") if k not in ("index", "truncated")]
    attrs = {"design": c.design, "thresholds": c.thresholds, "runs": c.runs}
    return _frame({k: sources[k] for k in names}, attrs, "Chart.runs_frame()")


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
    """Response.to_dataframe(): one row per frequency of each sweep, the schema's `response`
    columns (direction, freq_hz, the point's figures), with an ensemble its `response_ensemble`
    columns (direction, freq_hz, runs, each figure's X_p10 / X_median / X_p90, …)."""
    table = "response_ensemble" if r.runs and r.runs > 1 else "response"
    names = schema_names(table)
    rows: Dict[str, List[Any]] = {k: [] for k in names}
    for sweep in r.sweeps:
        sources: Dict[str, Any] = {k: v for k, v in sweep.items() if isinstance(v, np.ndarray) and v.ndim == 1}
        if isinstance(sweep.get("spread"), dict):
            sources.update(_flat_spread(sweep["spread"]))
        n = len(sources.get("freq_hz", []))
        sources["direction"] = [sweep["direction"]] * n
        sources["runs"] = [r.runs] * n
        if isinstance(sweep.get("verdict"), dict):
            sources["verdict"] = _verdict_labels(sweep["verdict"])
        for k, v in _table(table, sources).items():
            rows[k].extend(list(v))
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


def _attrs_json(d: Dict[str, Any]) -> Dict[str, Any]:
    """Scalars as they are, anything nested as JSON text (netCDF attrs hold no dicts)."""
    out: Dict[str, Any] = {}
    for k, v in d.items():
        if v is None:
            continue
        if isinstance(v, (dict, list, tuple)):
            out[k] = json.dumps(jsonable(v))
        elif isinstance(v, (bool, int, float, str, np.generic)):
            out[k] = v
    return out


def pulse_xarray(p: Any) -> Any:
    """Pulse.to_xarray(): p_pa on the dimension t_s; the scalars in attrs."""
    xr = _need("xarray", "Pulse.to_xarray()")
    d = p.as_dict()
    scalars = {k: v for k, v in d.items() if not isinstance(v, (np.ndarray, dict))}
    coords = {"t_s": ("t_s", np.asarray(p.t_s), {"units": "s", "long_name": "time after contact onset"})}
    data = {"p_pa": (("t_s",), np.asarray(p.p_pa), {"units": "Pa", "long_name": "sound pressure"})}
    return xr.Dataset(data, coords=coords, attrs=_attrs_json(scalars))


def run_xarray(run: Any) -> Any:
    """Run.to_xarray(): the time history on the dimension t_s; the metrics and design in attrs."""
    xr = _need("xarray", "Run.to_xarray()")
    h = dict(run.history)
    t = np.asarray(h.pop("t_s", np.zeros(0)))
    coords = {"t_s": ("t_s", t, {"units": "s", "long_name": "time"})}
    data = {k: (("t_s",), np.asarray(v), {"units": unit_of(k)}) for k, v in h.items()}
    d = run.as_dict()
    scalars = {k: v for k, v in d.items() if not isinstance(v, np.ndarray) and k not in ("impacts", "maxima", "history")}
    return xr.Dataset(data, coords=coords, attrs=_attrs_json(scalars))


def ensemble_xarray(e: Any) -> Any:
    """Ensemble.to_xarray(): every run on the dimension run, ball_position_m a coordinate."""
    xr = _need("xarray", "Ensemble.to_xarray()")
    cols = dict(e.ensemble)
    n = len(next(iter(cols.values()))) if cols else 0
    coords: Dict[str, Any] = {"run": ("run", np.arange(n), {"long_name": "run k (ball offset)"})}
    if "ball_position_m" in cols:
        coords["ball_position_m"] = ("run", np.asarray(cols.pop("ball_position_m")), {"units": "m"})
    data = {k: (("run",), np.asarray(v), {"units": unit_of(k)}) for k, v in cols.items()
            if isinstance(v, np.ndarray) and v.ndim == 1 and len(v) == n}
    attrs = {"design": e.design, "runs": e.runs, "zone": e.zone, "zone3_probability": e.zone3_probability,
             "agreement": e.agreement}
    return xr.Dataset(data, coords=coords, attrs=_attrs_json(attrs))


def response_xarray(r: Any) -> Any:
    """Response.to_xarray(): every figure on direction × freq_hz (each sweep's points in rising
    frequency; NaN where a sweep has no point at a frequency)."""
    xr = _need("xarray", "Response.to_xarray()")
    sweeps = [s for s in r.sweeps if "freq_hz" in s]
    freqs = np.unique(np.concatenate([np.asarray(s["freq_hz"], dtype=float) for s in sweeps])) if sweeps else np.zeros(0)
    names = [s["direction"] for s in sweeps]
    keys: List[str] = []
    for s in sweeps:
        for k, v in s.items():
            if k != "freq_hz" and isinstance(v, np.ndarray) and v.ndim == 1 and k not in keys:
                keys.append(k)
        if isinstance(s.get("spread"), dict):
            for k in _flat_spread(s["spread"]):
                if k not in keys:
                    keys.append(k)
    data: Dict[str, Any] = {}
    for k in keys:
        arr = np.full((len(sweeps), len(freqs)), np.nan)
        for i, s in enumerate(sweeps):
            v = s.get(k)
            if v is None and isinstance(s.get("spread"), dict):
                v = _flat_spread(s["spread"]).get(k)
            if v is None:
                continue
            at = np.searchsorted(freqs, np.asarray(s["freq_hz"], dtype=float))
            arr[i, at] = np.asarray(v, dtype=float)
        unit_key = k.rsplit("_", 1)[0] if k.endswith(("_p10", "_median", "_p90")) else k
        data[k] = (("direction", "freq_hz"), arr, {"units": unit_of(unit_key)})
    coords = {"direction": ("direction", names), "freq_hz": ("freq_hz", freqs, {"units": "Hz"})}
    attrs = {"design": r.design, "force_n": r.force_n, "runs": r.runs, "continuation": r.continuation}
    return xr.Dataset(data, coords=coords, attrs=_attrs_json(attrs))


def _study_metrics() -> List[str]:
    """The metric fields of a study cell (`thud sweep --vary --json`), in order: the schema's
    `sweep` columns after mass_kg and gap_m."""
    return schema_names("sweep")[2:]


def study_xarray(record: Dict[str, Any]) -> Any:
    """A study over any parameters (`thud.sweep(v0=[…], c1=[…])`) as an xarray Dataset: one
    dimension per varied parameter (its keyword; units in attrs), every metric of every cell
    (NaN where there is none; zone 0 = none), and with a force the steady amplitude and
    reduction. The design in attrs as JSON. Over one or two parameters it draws its figure
    (``to_svg``, ``to_pdf``: ``thud sweep --vary … --svg|--pdf``)."""
    xr = _need("xarray", "thud.sweep(**axes)")
    axes = record["axes"]
    # The dimensions are the CSV's columns (`v0_m_s`, `c1_n_s_m`), as `thud sweep --vary --csv`
    # heads them; the keywords (`v0`, `c1`) remain as deprecated aliases, indexed too, so
    # `.sel(c1=20)` still works.
    dims = tuple(a["column"] for a in axes)
    shape = tuple(len(a["values"]) for a in axes)
    coords: Dict[str, Any] = {dim: (dim, np.asarray(a["values"], dtype=float), {"units": a["unit"], "long_name": a["name"]})
                              for dim, a in zip(dims, axes)}
    aliases = []
    for dim, a in zip(dims, axes):
        old = a["name"].replace("-", "_")
        if old != dim and old not in coords:
            coords[old] = (dim, np.asarray(a["values"], dtype=float),
                           {"units": a["unit"], "long_name": a["name"], "deprecated": f"use {dim}"})
            aliases.append(old)
    cells = record["cells"]
    data: Dict[str, Any] = {}
    for k in _study_metrics():
        if k in ("n_impacts", "zone"):
            arr = np.array([c.get(k) or 0 for c in cells], dtype=np.int64)
        else:
            arr = np.array([np.nan if c.get(k) is None else c[k] for c in cells], dtype=float)
        data[k] = (dims, arr.reshape(shape), {"units": unit_of(k)})
    if any(c.get("steady") for c in cells):
        for k, name in (("amplitude_m", "steady_amplitude_m"), ("reduction_db", "steady_reduction_db")):
            arr = np.array([np.nan if not c.get("steady") or c["steady"].get(k) is None else c["steady"][k]
                            for c in cells], dtype=float)
            data[name] = (dims, arr.reshape(shape), {"units": unit_of(name)})
    ds = xr.Dataset(data, coords=coords, attrs={"design": json.dumps(record["design"])})
    for old in aliases:
        ds = ds.set_xindex(old)
    # Over one or two parameters it draws `thud sweep --vary … --svg|--pdf`'s figure.
    from ._diagram import study_dataset

    return study_dataset(ds, record)


def bifurcation_xarray(record: Dict[str, Any]) -> Any:
    """A bifurcation diagram (`thud.bifurcation(freq=[…], …)`) as an xarray Dataset: on
    point (each value of each sweep) × period the stroboscopic samples x_m, v_m_s, z_m,
    zdot_m_s at t = kT; per point the parameter's value, the direction and the orbit; the
    impacts on point × impact (phase, wall, u_in_m_s, u_out_m_s, period; NaN past a point's
    last impact); the bands in attrs as JSON. It draws its figure (``to_svg``, ``to_pdf``:
    ``thud bifurcation --svg|--pdf``)."""
    xr = _need("xarray", "thud.bifurcation()")
    b = record["bifurcation"]
    axis = b["axis"]
    name = axis["name"].replace("-", "_")
    points = b["points"]
    periods = max((len(p["samples"]) for p in points), default=0)
    most = max((len(p["impacts"]) for p in points), default=0)
    data: Dict[str, Any] = {}
    for k in ("x_m", "v_m_s", "z_m", "zdot_m_s"):
        arr = np.full((len(points), periods), np.nan)
        for i, p in enumerate(points):
            v = [s[k] for s in p["samples"]]
            arr[i, : len(v)] = v
        data[k] = (("point", "period"), arr, {"units": unit_of(k)})
    for k in ("phase", "wall", "u_in_m_s", "u_out_m_s", "period"):
        arr = np.full((len(points), most), np.nan)
        for i, p in enumerate(points):
            v = [float(imp[k]) for imp in p["impacts"]]
            arr[i, : len(v)] = v
        attrs = {"units": unit_of(k)} if k not in ("phase",) else {"units": "1", "long_name": "phase of the force (fraction of T)"}
        data["impact_" + k if k in ("period", "wall", "phase") else k] = (("point", "impact"), arr, attrs)
    data["amplitude_m"] = (("point",), np.array([p["amplitude_m"] for p in points], dtype=float), {"units": "m"})
    values = np.array([p["value"] for p in points], dtype=float)
    column = record.get("column", name)
    coords = {
        # Named as `thud bifurcation --csv`'s first column (`freq_hz`); the keyword (`freq`)
        # remains as a deprecated alias.
        column: ("point", values, {"units": axis["unit"], "long_name": axis["name"]}),
        "direction": ("point", [p["direction"] for p in points]),
        "orbit": ("point", [_orbit_label(p["orbit"]) for p in points]),
        "period": ("period", np.arange(periods)),
    }
    if column != name:
        coords[name] = ("point", values, {"units": axis["unit"], "long_name": axis["name"], "deprecated": f"use {column}"})
    attrs = {"design": json.dumps(record["design"]), "bands": json.dumps(b["bands"]),
             "transient_periods": b["settings"]["transient_periods"], "periods": b["settings"]["periods"],
             "parameter": axis["name"]}
    from ._diagram import bifurcation_dataset

    return bifurcation_dataset(xr.Dataset(data, coords=coords, attrs=attrs), record)


def _orbit_label(orbit: Dict[str, Any]) -> str:
    """The engine's label of a verdict (`2/1 sym`, `settled`, `chaotic`, `not settled`,
    `truncated`)."""
    kind = orbit.get("kind")
    if kind == "periodic":
        return f"{int(orbit['impacts'])}/{int(orbit['periods'])}" + (" sym" if orbit.get("symmetric") else "")
    return {"settled": "settled", "chaotic": "chaotic", "truncated": "truncated"}.get(str(kind), "not settled")


def _verdict_labels(v: Dict[str, Any]) -> List[str]:
    """The labels of a column of verdicts (the columns of their fields: kind, impacts, …)."""
    def at(key: str, i: int) -> Any:
        col = v.get(key)
        return None if col is None else col[i]
    return [_orbit_label({"kind": k, "impacts": at("impacts", i), "periods": at("periods", i),
                          "symmetric": at("symmetric", i)}) for i, k in enumerate(v.get("kind", []))]
