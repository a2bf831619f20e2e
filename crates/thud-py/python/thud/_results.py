"""The results of ``thud.orbit`` and ``thud.impact_map`` and the Dataset of
``thud.continuation``: built from the record the command line prints with ``--json`` (``thud
orbit``, ``thud impact-map``, ``thud continue``), handed over as its JSON text, so the numbers
are the command line's. A result keeps its record: it pickles as that text and two results are
equal when their records are."""

from __future__ import annotations

import json
from typing import Any, Dict, List, Optional, Tuple

import numpy as np

from ._frames import _need, _orbit_label, unit_of


def _columns(rows: List[Dict[str, Any]], keys: List[str]) -> Dict[str, np.ndarray]:
    """A list of records as a dict of NumPy arrays, one per key (whole numbers as int64, flags
    as bool, numbers as float64)."""
    out: Dict[str, np.ndarray] = {}
    for k in keys:
        values = [r[k] for r in rows]
        if all(isinstance(v, bool) for v in values) and values:
            out[k] = np.array(values, dtype=bool)
        elif all(isinstance(v, int) and not isinstance(v, bool) for v in values) and values:
            out[k] = np.array(values, dtype=np.int64)
        else:
            out[k] = np.array([np.nan if v is None else v for v in values], dtype=float)
    return out


class _Record:
    """A result held as the command line's JSON record."""

    _kind = ""

    def __init__(self, record: Dict[str, Any]) -> None:
        self._record = record

    def as_dict(self, json: bool = False) -> Dict[str, Any]:
        """The command line's ``--json`` record (plain lists, numbers and None)."""
        return _copy(self._record)

    def __reduce__(self) -> Any:
        from . import _restore

        return (_restore, (self._kind, json.dumps(self._record)))

    def __eq__(self, other: object) -> bool:
        return type(other) is type(self) and self._record == other._record  # type: ignore[attr-defined]

    def __hash__(self) -> int:
        return hash(json.dumps(self._record, sort_keys=True))


class _Drawn(_Record):
    """A result whose command draws it from its record (``--svg``, ``--pdf``)."""

    _figure = ""

    def _bytes(self, pdf: bool, size: Optional[Tuple[float, float]], title: bool) -> bytes:
        from . import _thud
        from ._files import look

        data: bytes = _thud._figure(self._figure, json.dumps(self._record), pdf, **look(size, title))
        return data

    def to_svg(self, path: Any, *, overwrite: bool = False, size: Optional[Tuple[float, float]] = None,
               title: bool = True) -> None:
        """The figure the command's ``--svg`` draws, byte for byte. An existing file is kept
        unless ``overwrite``; a symbolic link is never written through."""
        from ._files import write_file

        write_file(path, self._bytes(False, size, title), overwrite)

    def to_pdf(self, path: Any, *, overwrite: bool = False, size: Optional[Tuple[float, float]] = None,
               title: bool = True) -> None:
        """The figure as the command's ``--pdf`` writes it (one page, embedded font)."""
        from ._files import write_file

        write_file(path, self._bytes(True, size, title), overwrite)


def _copy(record: Dict[str, Any]) -> Dict[str, Any]:
    out: Dict[str, Any] = json.loads(json.dumps(record))
    return out


class Orbit(_Record):
    """A periodic orbit of a forced design found by shooting (``thud.orbit``; ``thud orbit
    --json``): its period n (forcing periods) and impacts m, the state at the force's phase 0,
    its amplitude, its impacts, its Floquet multipliers and stability. SI units."""

    _kind = "Orbit"

    def __init__(self, record: Dict[str, Any]) -> None:
        super().__init__(record)
        r = record
        #: The design as run (the command line's JSON "design" object).
        self.design: Dict[str, Any] = r["design"]
        #: The orbit's period in forcing periods, n.
        self.periods: int = int(r["periods"])
        #: Impacts over the n periods, m.
        self.impacts_per_orbit: int = int(r["impacts_per_orbit"])
        #: Whether x(t + T/2) = −x(t).
        self.symmetric: bool = bool(r["symmetric"])
        #: The state at the force's phase 0: x (m), x' (m/s), z = y − x (m), z' (m/s).
        self.x_m: float = float(r["x_m"])
        self.v_m_s: float = float(r["v_m_s"])
        self.z_m: float = float(r["z_m"])
        self.zdot_m_s: float = float(r["zdot_m_s"])
        #: Largest |x| over the orbit (m).
        self.amplitude_m: float = float(r["amplitude_m"])
        #: The main mass without the ball, in its steady state (m); None where unbounded.
        self.amplitude_linear_m: Optional[float] = r.get("amplitude_linear_m")
        #: Every impact: period, phase (fraction of T), wall (±1), u_in_m_s, u_out_m_s.
        self.impacts: Dict[str, np.ndarray] = _columns(r["impacts"], ["period", "phase", "wall", "u_in_m_s", "u_out_m_s"])
        #: The Floquet multipliers, largest modulus first (complex).
        self.multipliers: np.ndarray = np.array([complex(m["re"], m["im"]) for m in r["multipliers"]], dtype=complex)
        #: Every |λ| < 1.
        self.stable: bool = bool(r["stable"])
        #: How the largest multiplier crosses (or would cross) the unit circle: "fold",
        #: "period_doubling" or "neimark_sacker".
        self.critical: str = str(r["critical"])
        #: |Pⁿ(s) − s| at the orbit, the largest component (m or m/s).
        self.residual: float = float(r["residual"])
        #: Newton iterations taken.
        self.iterations: int = int(r["iterations"])
        #: Forcing periods simulated to find it and its multipliers.
        self.periods_simulated: float = float(r["periods_simulated"])

    @property
    def label(self) -> str:
        """``3/1``, ``2/1 sym``: impacts per periods."""
        return f"{self.impacts_per_orbit}/{self.periods}" + (" sym" if self.symmetric else "")

    def to_dataframe(self) -> Any:
        """The impacts as a table, one row per impact (the columns of ``thud orbit --csv``'s
        impact part: impact, period, phase, wall, u_in_m_s, u_out_m_s); the orbit's scalars in
        ``.attrs``. Needs pandas."""
        pd = _need("pandas", "Orbit.to_dataframe()")
        i = self.impacts
        df = pd.DataFrame({"impact": np.arange(len(i["period"])), "period": i["period"], "phase": i["phase"],
                           "wall": i["wall"], "u_in_m_s": i["u_in_m_s"], "u_out_m_s": i["u_out_m_s"]})
        df.attrs.update({"orbit": self.label, "amplitude_m": self.amplitude_m, "stable": self.stable,
                         "critical": self.critical, "design": self.design})
        return df

    def to_xarray(self) -> Any:
        """The impacts on the dimension impact, the multipliers (re, im, abs) on multiplier;
        the orbit's scalars in ``.attrs``. Needs xarray."""
        xr = _need("xarray", "Orbit.to_xarray()")
        i = self.impacts
        data = {
            "period": (("impact",), i["period"]),
            "phase": (("impact",), i["phase"], {"units": "1", "long_name": "phase of the force (fraction of T)"}),
            "wall": (("impact",), i["wall"]),
            "u_in_m_s": (("impact",), i["u_in_m_s"], {"units": "m/s"}),
            "u_out_m_s": (("impact",), i["u_out_m_s"], {"units": "m/s"}),
            "multiplier_re": (("multiplier",), self.multipliers.real),
            "multiplier_im": (("multiplier",), self.multipliers.imag),
            "multiplier_abs": (("multiplier",), np.abs(self.multipliers)),
        }
        attrs = {"orbit": self.label, "periods": self.periods, "impacts_per_orbit": self.impacts_per_orbit,
                 "symmetric": int(self.symmetric), "amplitude_m": self.amplitude_m, "stable": int(self.stable),
                 "critical": self.critical, "x_m": self.x_m, "v_m_s": self.v_m_s, "z_m": self.z_m,
                 "zdot_m_s": self.zdot_m_s, "design": json.dumps(self.design)}
        return xr.Dataset(data, attrs=attrs)

    def __repr__(self) -> str:
        lead = float(np.abs(self.multipliers[0])) if len(self.multipliers) else 0.0
        return (f"Orbit({self.label}, amplitude {self.amplitude_m:.6g} m, "
                f"{'stable' if self.stable else 'unstable'}, largest |λ| {lead:.4g})")


class ImpactMap(_Drawn):
    """A forced design's stroboscopic samples and impacts over its sampled periods after a
    transient, and the orbit's type (``thud.impact_map``; ``thud impact-map --json``)."""

    _kind = "ImpactMap"
    _figure = "impact_map"

    def __init__(self, record: Dict[str, Any]) -> None:
        super().__init__(record)
        r = record
        #: The design as run.
        self.design: Dict[str, Any] = r["design"]
        #: transient_periods and periods.
        self.settings: Dict[str, int] = dict(r["settings"])
        #: The orbit's type: ``3/1``, ``2/1 sym``, ``chaotic``, ``not settled``, ``truncated``.
        self.orbit: str = _orbit_label(r["orbit"])
        #: Largest |x| over the sampled periods (m).
        self.amplitude_m: float = float(r["amplitude_m"])
        #: Whether a work cap stopped the run before its end.
        self.truncated: bool = bool(r["truncated"])
        #: The state at t = kT: x_m, v_m_s, z_m, zdot_m_s.
        self.samples: Dict[str, np.ndarray] = _columns(r["samples"], ["x_m", "v_m_s", "z_m", "zdot_m_s"])
        impacts = r["impacts"]
        keys = list(impacts[0].keys()) if impacts else ["phase", "wall", "u_in_m_s", "u_out_m_s", "period"]
        #: Every impact of the sampled periods (phase of the force, wall, speeds, period).
        self.impacts: Dict[str, np.ndarray] = _columns(impacts, keys)

    def to_dataframe(self) -> Any:
        """The impacts as a table (one row per impact); the orbit and design in ``.attrs``."""
        pd = _need("pandas", "ImpactMap.to_dataframe()")
        df = pd.DataFrame(self.impacts)
        df.attrs.update({"orbit": self.orbit, "amplitude_m": self.amplitude_m, "design": self.design})
        return df

    def to_xarray(self) -> Any:
        """The samples on the dimension period, the impacts on impact; the orbit in attrs."""
        xr = _need("xarray", "ImpactMap.to_xarray()")
        data: Dict[str, Any] = {k: (("period",), v, {"units": unit_of(k)}) for k, v in self.samples.items()}
        for k, v in self.impacts.items():
            data["impact_" + k if k in ("period", "wall", "phase") else k] = (("impact",), v)
        attrs = {"orbit": self.orbit, "amplitude_m": self.amplitude_m, "truncated": int(self.truncated),
                 "transient_periods": self.settings["transient_periods"], "periods": self.settings["periods"],
                 "design": json.dumps(self.design)}
        return xr.Dataset(data, attrs=attrs)

    def __repr__(self) -> str:
        n = len(next(iter(self.impacts.values()), []))
        return f"ImpactMap({self.orbit}, amplitude {self.amplitude_m:.6g} m, {n} impacts)"


class Basins(_Drawn):
    """The basins of attraction of a forced design over the ball's start (``thud.basins``;
    ``thud basins --json``): per start (y0, w0) the attractor it settles on and the amplitude it
    reached; the attractors with their orbit type and amplitude."""

    _kind = "Basins"
    _figure = "basins"

    def __init__(self, record: Dict[str, Any]) -> None:
        super().__init__(record)
        r = record
        #: The design as run.
        self.design: Dict[str, Any] = r["design"]
        #: The ball's starting offsets (m) and velocities (m/s).
        self.y0_m: np.ndarray = np.array(r["y0_m"], dtype=float)
        self.w0_m_s: np.ndarray = np.array(r["w0_m_s"], dtype=float)
        shape = (len(self.w0_m_s), len(self.y0_m))
        #: The attractor of each start, shape (len(w0_m_s), len(y0_m)).
        self.attractor: np.ndarray = np.array(r["cells"], dtype=np.int64).reshape(shape)
        #: The amplitude each start reached (m), same shape.
        self.amplitude_m: np.ndarray = np.array(r["amplitudes_m"], dtype=float).reshape(shape)
        #: The attractors, in id order (their orbit type, amplitude, …).
        self.attractors: List[Dict[str, Any]] = list(r["attractors"])

    def to_dataframe(self) -> Any:
        """One row per start, the columns of ``thud basins --csv`` (y0_m, w0_m_s, attractor,
        orbit, amplitude_m). Needs pandas."""
        pd = _need("pandas", "Basins.to_dataframe()")
        w, y = np.meshgrid(self.w0_m_s, self.y0_m, indexing="ij")
        labels = [a.get("label", "") for a in self.attractors]
        ids = self.attractor.ravel()
        return pd.DataFrame({"y0_m": y.ravel(), "w0_m_s": w.ravel(), "attractor": ids,
                             "orbit": [labels[i] if i < len(labels) else "" for i in ids],
                             "amplitude_m": self.amplitude_m.ravel()})

    def to_xarray(self) -> Any:
        """attractor and amplitude_m on w0_m_s × y0_m. Needs xarray."""
        xr = _need("xarray", "Basins.to_xarray()")
        coords = {"w0_m_s": ("w0_m_s", self.w0_m_s, {"units": "m/s"}), "y0_m": ("y0_m", self.y0_m, {"units": "m"})}
        data = {"attractor": (("w0_m_s", "y0_m"), self.attractor),
                "amplitude_m": (("w0_m_s", "y0_m"), self.amplitude_m, {"units": "m"})}
        return xr.Dataset(data, coords=coords, attrs={"attractors": json.dumps(self.attractors),
                                                      "design": json.dumps(self.design)})

    def __repr__(self) -> str:
        return f"Basins({self.attractor.shape[1]} × {self.attractor.shape[0]} starts, {len(self.attractors)} attractors)"


class Restitution(_Record):
    """The restitution R = u_out/U0 of one isolated contact against the impact mass
    (``thud.restitution``; ``thud restitution``), and with a target R the c1 that gives it."""

    _kind = "Restitution"

    def __init__(self, record: Dict[str, Any]) -> None:
        super().__init__(record)
        r = record
        #: The design as run.
        self.design: Dict[str, Any] = r["design"]
        #: The approach speed U0 (m/s).
        self.u0_m_s: float = float(r["u0_m_s"])
        #: The wanted restitution, if given.
        self.target: Optional[float] = r.get("target")
        #: The impact masses (kg).
        self.masses_kg: np.ndarray = np.array(r["masses_kg"], dtype=float)
        #: R at each mass.
        self.restitution: np.ndarray = np.array(r["restitution"], dtype=float)
        c1 = r.get("c1_for_target_n_s_m")
        #: The c1 (N·s/m) that gives the target R at each mass; None without a target.
        self.c1_for_target_n_s_m: Optional[np.ndarray] = None if c1 is None else np.array(c1, dtype=float)

    def to_dataframe(self) -> Any:
        """The columns of ``thud restitution --csv``: mass_g (the paper's axis), restitution, and
        with a target c1_for_target_n_s_m. Needs pandas."""
        pd = _need("pandas", "Restitution.to_dataframe()")
        cols: Dict[str, Any] = {"mass_g": self.masses_kg * 1e3, "restitution": self.restitution}
        if self.c1_for_target_n_s_m is not None:
            cols["c1_for_target_n_s_m"] = self.c1_for_target_n_s_m
        return pd.DataFrame(cols)

    def to_xarray(self) -> Any:
        """restitution (and c1_for_target_n_s_m) on mass_kg. Needs xarray."""
        xr = _need("xarray", "Restitution.to_xarray()")
        data: Dict[str, Any] = {"restitution": (("mass_kg",), self.restitution)}
        if self.c1_for_target_n_s_m is not None:
            data["c1_for_target_n_s_m"] = (("mass_kg",), self.c1_for_target_n_s_m, {"units": "N·s/m"})
        return xr.Dataset(data, coords={"mass_kg": ("mass_kg", self.masses_kg, {"units": "kg"})},
                          attrs={"u0_m_s": self.u0_m_s, "design": json.dumps(self.design)})

    def _figure(self, pdf: bool, size: Optional[Tuple[float, float]], title: bool) -> bytes:
        from ._files import look, render

        return render("restitution", self.design, pdf, u0=self.u0_m_s,
                      masses_kg=[float(m) for m in self.masses_kg], **look(size, title))

    def to_svg(self, path: Any, *, overwrite: bool = False, size: Optional[Tuple[float, float]] = None,
               title: bool = True) -> None:
        """R against the impact mass as SVG (Fig 13): ``thud export svg restitution`` over these
        masses at this U0. An existing file is kept unless ``overwrite``."""
        from ._files import write_file

        write_file(path, self._figure(False, size, title), overwrite)

    def to_pdf(self, path: Any, *, overwrite: bool = False, size: Optional[Tuple[float, float]] = None,
               title: bool = True) -> None:
        """R against the impact mass as a one-page PDF (``thud export pdf restitution``)."""
        from ._files import write_file

        write_file(path, self._figure(True, size, title), overwrite)

    def __repr__(self) -> str:
        return f"Restitution({len(self.masses_kg)} masses at U0 {self.u0_m_s:g} m/s)"


def _restore_record(kind: str, state: str) -> Any:
    """A result again from its pickled state (its record's JSON text)."""
    record = json.loads(state)
    kinds = {"Orbit": Orbit, "ImpactMap": ImpactMap, "Basins": Basins, "Restitution": Restitution}
    if kind not in kinds:
        raise ValueError(f"not a thud result kind: {kind!r}")
    return kinds[kind](record)


def continuation_xarray(record: Dict[str, Any]) -> Any:
    """A continued branch (``thud.continuation(freq=(3, 8), …)``) as an xarray Dataset: on the
    dimension point the parameter's value (coordinate named as ``thud continue --csv``'s
    first column, e.g. ``freq_hz``), the orbit, stability, largest |λ|, impacts per orbit,
    amplitude and the state at phase 0; the special points (fold, period doubling,
    Neimark–Sacker, branch point, grazing) on the dimension special; why the branch ended
    early, if it did, in attrs. The Dataset draws its figure (``ds.to_svg(path)``,
    ``ds.to_pdf(path)``: ``thud continue --svg|--pdf``, byte for byte)."""
    xr = _need("xarray", "thud.continuation()")
    name, unit = record["name"], record["unit"]
    col = record["column"]
    pts = record["points"]
    c = _columns(pts, ["value", "periods", "impacts_per_orbit", "stable", "multiplier_abs_max", "amplitude_m",
                       "x_m", "v_m_s", "z_m", "zdot_m_s"])
    data: Dict[str, Any] = {}
    for k in ("amplitude_m", "x_m", "v_m_s", "z_m", "zdot_m_s"):
        data[k] = (("point",), c[k], {"units": unit_of(k)})
    data["multiplier_abs_max"] = (("point",), c["multiplier_abs_max"])
    data["stable"] = (("point",), np.array([bool(p["stable"]) for p in pts], dtype=bool))
    data["periods"] = (("point",), c["periods"])
    data["impacts_per_orbit"] = (("point",), c["impacts_per_orbit"])
    specials = record["specials"]
    data["special_kind"] = (("special",), np.array([s["kind"] for s in specials], dtype=object))
    data["special_" + col] = (("special",), np.array([s["value"] for s in specials], dtype=float), {"units": unit})
    data["special_amplitude_m"] = (("special",), np.array([s["amplitude_m"] for s in specials], dtype=float),
                                   {"units": "m"})
    coords = {col: ("point", c["value"], {"units": unit, "long_name": name}),
              "orbit": ("point", np.array([p["orbit"] for p in pts], dtype=object))}
    attrs = {"parameter": name, "design": json.dumps(record["design"]),
             "ended": record["ended"] if record.get("ended") is not None else ""}
    from ._diagram import continuation_dataset

    return continuation_dataset(xr.Dataset(data, coords=coords, attrs=attrs), record)



class _Fit(Dict[str, Any]):
    """A fit as the command line's ``thud fit … --json`` object: a dict of its keys (``f["zeta"]``),
    with tables. Pickles to an equal dict of the same class."""

    def as_dict(self, json: bool = False) -> Dict[str, Any]:
        """The ``--json`` object (a plain dict copy)."""
        return _copy(dict(self))

    def _scalars(self) -> Dict[str, Any]:
        return {k: v for k, v in self.items() if isinstance(v, (bool, int, float, str)) or v is None}


class StructureFit(_Fit):
    """The structure's fit (``thud.fit_structure``; ``thud fit structure --json``): f_n_hz, zeta,
    k_n_m, c_n_s_m with their ``_stderr``, main_mass_kg, residual_rms, converged, …"""

    def to_dataframe(self) -> Any:
        """One row: every number and word of the fit, the ``--json`` keys as columns. Needs pandas."""
        pd = _need("pandas", "StructureFit.to_dataframe()")
        return pd.DataFrame([self._scalars()])

    def to_xarray(self) -> Any:
        """The fitted values as 0-d variables (their standard errors beside them), the rest in
        attrs. Needs xarray."""
        xr = _need("xarray", "StructureFit.to_xarray()")
        scalars = self._scalars()
        data = {k: v for k, v in scalars.items() if isinstance(v, float)}
        attrs = {k: (str(v) if isinstance(v, bool) or v is None else v) for k, v in scalars.items() if k not in data}
        return xr.Dataset({k: ((), v) for k, v in data.items()}, attrs=attrs)

    def __repr__(self) -> str:
        return f"StructureFit(f_n {self.get('f_n_hz', float('nan')):.6g} Hz, zeta {self.get('zeta', float('nan')):.4g})"


class DamperFit(_Fit):
    """The damper's fit (``thud.fit_damper``; ``thud fit damper --json``): c1_n_s_m with its
    standard error and 95 % interval c1_n_s_m_ci, restitution (same), residual_rms, the
    measured and model envelopes, note, …"""

    def to_dataframe(self) -> Any:
        """The envelopes, one row a period: t_s (the period's start), measured_envelope_m,
        model_envelope_m; the fit's numbers in ``.attrs``. Needs pandas."""
        pd = _need("pandas", "DamperFit.to_dataframe()")
        measured = list(self.get("measured_envelope_m") or [])
        model = list(self.get("model_envelope_m") or [])
        n = max(len(measured), len(model))
        pad = lambda v: v + [float("nan")] * (n - len(v))  # noqa: E731
        period = float(self.get("envelope_period_s") or 0.0)
        df = pd.DataFrame({"t_s": [i * period for i in range(n)], "measured_envelope_m": pad(measured),
                           "model_envelope_m": pad(model)})
        df.attrs.update(self._scalars())
        return df

    def to_xarray(self) -> Any:
        """The envelopes on t_s (s), c1 and restitution with their intervals as variables, the
        rest in attrs. Needs xarray."""
        xr = _need("xarray", "DamperFit.to_xarray()")
        df = self.to_dataframe()
        ds = xr.Dataset({"measured_envelope_m": (("t_s",), df["measured_envelope_m"].to_numpy(), {"units": "m"}),
                         "model_envelope_m": (("t_s",), df["model_envelope_m"].to_numpy(), {"units": "m"})},
                        coords={"t_s": ("t_s", df["t_s"].to_numpy(), {"units": "s"})})
        for key in ("c1_n_s_m_ci", "restitution_ci"):
            if key in self:
                ds[key] = (("bound",), np.array(self[key], dtype=float))
        ds = ds.assign_coords(bound=["low", "high"]) if "bound" in ds.dims else ds
        scalars = self._scalars()
        for k, v in scalars.items():
            if isinstance(v, float):
                ds[k] = ((), v)
            else:
                ds.attrs[k] = str(v) if isinstance(v, bool) or v is None else v
        return ds

    def __repr__(self) -> str:
        return f"DamperFit(c1 {self.get('c1_n_s_m', float('nan')):.6g} N·s/m)"
