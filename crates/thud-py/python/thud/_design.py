"""The design search from Python: ``thud.design(...)`` (``thud design``) returns a ``Front``;
``thud.Designer(...)`` is its ask/tell form, for designs evaluated elsewhere (Dask, a cluster).

The problem is given in the command line's words: ``vary="mass=20g:120g"`` (or a list),
``choose="sphere=steel,acrylic,nylon"``, ``minimize="spl_max_db"``,
``maximize="inclination_cm_s"``, ``require="mass<=60g"``, ``over="freqs=4.5Hz:5.5Hz:21"``,
``evaluations``, ``seed``, ``reference=(106, 0)``; every other keyword is the base design's,
as for ``simulate``. A ``Front`` holds the record ``thud design --json`` prints, so its numbers
are the command line's for the same inputs and seed."""

from __future__ import annotations

import inspect
import json
from typing import Any, Dict, List, Mapping, Optional, Sequence, Union

from . import _thud
from ._frames import _need

#: A column of the results a told result carries, read from a ``Run``.
_STEADY = {"steady_amplitude_m": "amplitude_m", "steady_reduction_db": "reduction_db", "steady_leq_db": "leq_db"}

#: The search's own keywords (the rest are the base design's).
_SEARCH = ("vary", "choose", "minimize", "maximize", "require", "over", "evaluations", "seed", "reference",
           "no_limit")


class Front:
    """The Pareto front of a design search (``thud.design``; ``thud design --json``): every
    non-dominated design with its variables, objectives and constraint margins, and the
    search's budget, seed, reference point and hypervolume. SI units, columns named as the
    command line's CSV (``mass_kg``, ``spl_max_db``, ``margin_mass_le``)."""

    def __init__(self, record: Dict[str, Any]) -> None:
        record = dict(record)
        extra = record.pop("python", None) or {}
        self._record = record
        self._keywords: List[str] = list(extra.get("keywords", [v["name"].replace("-", "_")
                                                              for v in record["variables"]]))
        self._counts: List[bool] = list(extra.get("counts", [False] * len(self._keywords)))
        self._margin_columns: List[str] = list(extra.get("margin_columns", record["constraints"]))
        r = record
        #: The base design (the command line's JSON "design" object).
        self.design: Dict[str, Any] = r["design"]
        #: The variables: name, column and unit with from/to, or options.
        self.variables: List[Dict[str, Any]] = r["variables"]
        #: The objectives: column and sense ("minimize" / "maximize").
        self.objectives: List[Dict[str, Any]] = r["objectives"]
        #: The constraints as typed.
        self.constraints: List[str] = list(r["constraints"])
        #: The forcing frequencies of the band (Hz), empty without one.
        self.band_hz: List[float] = list(r.get("band_hz", []))
        #: Designs evaluated.
        self.evaluations: int = int(r["evaluations"])
        #: The budget (designs evaluated at most).
        self.budget: int = int(r["budget"])
        self.seed: int = int(r["seed"])
        #: Whether the search stopped before its end (an unfinished ask/tell search).
        self.partial: bool = bool(r["partial"])
        #: The hypervolume's reference point (two objectives), in the columns' units.
        self.reference: Optional[List[float]] = r.get("reference")
        #: The front's hypervolume against the reference (two objectives).
        self.hypervolume: Optional[float] = r.get("hypervolume")
        #: When no design is feasible: which constraint binds.
        self.binding: Optional[str] = r.get("binding")

    def __len__(self) -> int:
        return len(self._record["front"])

    @property
    def designs(self) -> List[Dict[str, Any]]:
        """The front designs in order of the first objective: index (order of evaluation),
        variables, objectives and margins, each a dict by column."""
        out: List[Dict[str, Any]] = json.loads(json.dumps(self._record["front"]))
        return out

    def keywords(self, k: int) -> Dict[str, Union[float, int, str]]:
        """The ``k``-th front design's variables as keywords (``{"mass": 0.05, "gap": 0.021}``):
        with the base design's keywords, ``thud.simulate(preset=…, **front.keywords(k))`` runs it
        and gives exactly its objectives."""
        row = self._record["front"][k]
        out: Dict[str, Union[float, int, str]] = {}
        for kw, v, count in zip(self._keywords, self.variables, self._counts):
            x = row["variables"][v["column"]]
            out[kw] = int(x) if count else x
        return out

    def _columns(self) -> Dict[str, List[Any]]:
        rows = self._record["front"]
        cols: Dict[str, List[Any]] = {"index": [r["index"] for r in rows]}
        for v in self.variables:
            cols[v["column"]] = [r["variables"][v["column"]] for r in rows]
        for o in self.objectives:
            cols[o["column"]] = [r["objectives"][o["column"]] for r in rows]
        for text, col in zip(self.constraints, self._margin_columns):
            cols[col] = [r["margins"][text] for r in rows]
        return cols

    def _attrs(self) -> Dict[str, Any]:
        return {"evaluations": self.evaluations, "budget": self.budget, "seed": self.seed,
                "partial": int(self.partial),
                "reference": list(self.reference) if self.reference is not None else [],
                "hypervolume": self.hypervolume if self.hypervolume is not None else float("nan"),
                "objectives": ", ".join(f"{o['sense']} {o['column']}" for o in self.objectives),
                "constraints": ", ".join(self.constraints), "design": json.dumps(self.design)}

    def to_dataframe(self) -> Any:
        """The front as a table, one row per design: index, the variables, the objectives and
        the margins (the columns of ``thud design --csv``); the search in ``.attrs``. Needs
        pandas."""
        pd = _need("pandas", "Front.to_dataframe()")
        cols = self._columns()
        df = pd.DataFrame({k: [float("nan") if x is None else x for x in v] if k != "index" else v
                           for k, v in cols.items()})
        df.attrs.update(self._attrs())
        return df

    def to_xarray(self) -> Any:
        """The front on the dimension design (its position along the front), with its index,
        variables (units as the columns'), objectives and margins as variables; the search in
        ``.attrs``. Needs xarray."""
        xr = _need("xarray", "Front.to_xarray()")
        import numpy as np

        cols = self._columns()
        units = {v["column"]: v.get("unit", "") for v in self.variables}
        data: Dict[str, Any] = {}
        for k, values in cols.items():
            if k == "index":
                data[k] = (("design",), np.array(values, dtype=np.int64))
            elif values and all(isinstance(x, str) for x in values):
                data[k] = (("design",), np.array(values, dtype=object))
            else:
                arr = np.array([np.nan if x is None else x for x in values], dtype=float)
                data[k] = (("design",), arr, {"units": units[k]} if units.get(k) else {})
        return xr.Dataset(data, coords={"design": np.arange(len(self))}, attrs=self._attrs())

    def as_dict(self, json: bool = False) -> Dict[str, Any]:
        """The command line's ``thud design --json`` record (plain lists, numbers and None)."""
        return _copy(self._record)

    def __reduce__(self) -> Any:
        return (_restore_front, (self._text(),))

    def _text(self) -> str:
        r = dict(self._record)
        r["python"] = {"keywords": self._keywords, "counts": self._counts, "margin_columns": self._margin_columns}
        return json.dumps(r)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Front) and self._record == other._record

    def __hash__(self) -> int:
        return hash(json.dumps(self._record, sort_keys=True))

    def __repr__(self) -> str:
        hv = f", hypervolume {self.hypervolume:.6g}" if self.hypervolume is not None else ""
        part = ", partial" if self.partial else ""
        return f"Front({len(self)} designs of {self.evaluations} evaluated, seed {self.seed}{hv}{part})"


def _copy(record: Dict[str, Any]) -> Dict[str, Any]:
    out: Dict[str, Any] = json.loads(json.dumps(record))
    return out


def _restore_front(state: str) -> Front:
    """A front again from its pickled state (its record's JSON text)."""
    return Front(json.loads(state))


def _error(param: str, message: str) -> Exception:
    """A ParameterError naming `param` (its ``.param``), as the engine's."""
    e = _thud.ParameterError(message)
    e.param = param  # type: ignore[attr-defined]
    return e


def design(**params: Any) -> Front:
    from ._wrap import with_progress

    try:
        text = _thud._design(**with_progress(params, "design"))
    except BaseException as stop:
        # Ctrl-C (or the progress callback's exception): the front found so far rides on it.
        found = getattr(stop, "_thud_front", None)
        if isinstance(found, str):
            del stop._thud_front  # type: ignore[attr-defined]
            stop.front = Front(json.loads(found))  # type: ignore[attr-defined]
        raise
    return Front(json.loads(text))


def _read(result: Any, column: str) -> Optional[float]:
    """The value of `column` in one told result: a mapping by column, or a ``Run``."""
    if isinstance(result, Mapping):
        if column not in result:
            raise _error("results", f"invalid results: a result has no {column!r}; give every column of "
                                    f"Designer.columns")
        v = result[column]
    elif column in _STEADY:
        steady = getattr(result, "steady", None)
        v = steady.get(_STEADY[column]) if isinstance(steady, Mapping) else None
    elif hasattr(result, column):
        v = getattr(result, column)
    else:
        raise _error("results", f"invalid results: expected a mapping by column or a thud.Run, not "
                                f"{type(result).__name__}")
    if v is None:
        return None
    try:
        return float(v)
    except (TypeError, ValueError, OverflowError):
        raise _error("results", f"invalid results: {column} is {v!r}, not a number") from None


class Designer:
    """The design search in ask/tell form, for designs evaluated elsewhere (Dask, a cluster):
    ``d = thud.Designer(preset="paper-table3", vary=["mass=20g:120g", "gap=1cm:6cm"],
    minimize="spl_max_db", maximize="inclination_cm_s", evaluations=400, seed=1)``, then
    ``xs = d.ask(n)`` (each a dict of keywords), evaluate ``thud.simulate(**d.base, **x)``
    anywhere, ``d.tell(xs, results)``, until ``d.done``; ``d.result()`` is the ``Front``.

    The same NSGA-II as ``thud.design`` (same operators, generations and seed): told the
    results ``thud.simulate`` gives, it finds exactly ``thud.design``'s front. The search waits
    for a whole batch (its population) to be told before it asks for the next, so ``ask(n)``
    returns fewer than n points (or none) while points asked are still out.

    With a band (``over="freqs=4.5Hz:5.5Hz:21"``, a forced design) a point is one run per
    frequency of ``d.band_hz``: ``[thud.simulate(**kw) for kw in d.runs(x)]``, told as that
    list; each objective and result constraint is then its worst over the band, as
    ``thud.design --over`` takes it."""

    def __init__(self, **params: Any) -> None:
        self._native = _thud._Designer(**params)
        self._base: Dict[str, Any] = {k: v for k, v in params.items() if k not in _SEARCH and v is not None}
        record = json.loads(self._native.result())
        self._front_keys: List[str] = record["python"]["keywords"]
        self._band: List[float] = list(self._native.band_hz())

    @property
    def base(self) -> Dict[str, Any]:
        """The base design's keywords (``preset``, ``design`` and the design's own), to run a
        point with: ``thud.simulate(**d.base, **x)``."""
        return dict(self._base)

    @property
    def band_hz(self) -> List[float]:
        """The forcing frequencies of the band (Hz), one run of each point per frequency;
        empty without a band."""
        return list(self._band)

    def runs(self, x: Mapping[str, Union[float, int, str]]) -> List[Dict[str, Any]]:
        """The keywords of each run of the point ``x`` (as ``ask`` gave it), for
        ``thud.simulate(**kw)``: the base design with the point's values, once, or once per
        frequency of the band (``freq`` set), in the band's order."""
        one = {**self._base, **x}
        if not self._band:
            return [one]
        return [{**one, "freq": f} for f in self._band]

    @property
    def columns(self) -> List[str]:
        """The result columns a told result carries (the objectives', then the constraints')."""
        out: List[str] = self._native.columns()
        return out

    @property
    def done(self) -> bool:
        """Whether the search is over (its budget spent or its generations run)."""
        out: bool = self._native.done()
        return out

    @property
    def outstanding(self) -> int:
        """Points asked and not told yet."""
        out: int = self._native.outstanding()
        return out

    def ask(self, n: int = 1) -> List[Dict[str, Union[float, int, str]]]:
        """Up to ``n`` points to evaluate, each the variables as keywords (``{"mass": 0.05,
        "gap": 0.021}``); fewer, or none, while the batch under way waits for points already
        asked; none once ``done``."""
        if isinstance(n, bool) or not isinstance(n, int) or n < 1:
            raise _error("n", f"invalid n: expected a whole number ≥ 1, not {n!r}")
        # "Up to n": a count past what any search holds asks for all there is.
        rows = self._native.ask(min(n, 2**63 - 1))
        return [dict(zip(self._front_keys, row)) for row in rows]

    def tell(self, xs: Sequence[Mapping[str, Union[float, int, str]]], results: Sequence[Any]) -> None:
        """Tells what the points ``xs`` (as ``ask`` gave them) gave: each result a ``thud.Run``,
        a mapping by column (``{"spl_max_db": 99.7, "inclination_cm_s": 0.79}``, None where the
        run has no value), or an exception or text saying why the point could not be run. With
        a band, each result is a list of those, one per frequency of ``band_hz`` in its order
        (the runs of ``runs(x)``)."""
        if len(xs) != len(results):
            raise _error("results", f"invalid results: {len(results)} results for {len(xs)} points")
        columns = self.columns
        for x, r in zip(xs, results):
            try:
                values = [x[k] for k in self._front_keys]
            except (KeyError, TypeError):
                raise _error("xs", f"invalid xs: expected a point as ask gave it (keys "
                                  f"{', '.join(self._front_keys)}), not {x!r}") from None
            told: Union[str, List[List[Optional[float]]]]
            if isinstance(r, (str, BaseException)):
                told = str(r) or type(r).__name__
            elif self._band:
                if isinstance(r, Mapping) or not isinstance(r, Sequence) or len(r) != len(self._band):
                    raise _error("results", f"invalid results: a point of a band is a list of "
                                            f"{len(self._band)} results, one per frequency of band_hz")
                told = [[_read(run, c) for c in columns] for run in r]
            else:
                told = [[_read(r, c) for c in columns]]
            self._native.tell(values, told)

    def result(self) -> Front:
        """The front of every design told so far (``partial`` until ``done``)."""
        return Front(json.loads(self._native.result()))

    def __repr__(self) -> str:
        f = self.result()
        return f"Designer({f.evaluations} of {f.budget} evaluated, {self.outstanding} out, " \
               f"{'done' if self.done else 'running'})"


def _signature() -> inspect.Signature:
    """``design``'s keywords: the base design's (the engine's table), then the search's."""
    from ._wrap import _OPTION_TYPES, _annotation

    P = inspect.Parameter
    table = _thud._parameters()
    texts = Union[str, Sequence[str], None]
    params = [P("preset", P.KEYWORD_ONLY, default=None, annotation=_OPTION_TYPES["preset"]),
              P("design", P.KEYWORD_ONLY, default=None, annotation=_OPTION_TYPES["design"])]
    params += [P(row["name"], P.KEYWORD_ONLY, default=None, annotation=_annotation(row)) for row in table["design"]]
    params += [P(n, P.KEYWORD_ONLY, default=None, annotation=texts)
               for n in ("vary", "choose", "minimize", "maximize", "require")]
    params += [P("over", P.KEYWORD_ONLY, default=None, annotation=Optional[str]),
               P("evaluations", P.KEYWORD_ONLY, default=400, annotation=Union[int, str]),
               P("seed", P.KEYWORD_ONLY, default=0, annotation=int),
               P("reference", P.KEYWORD_ONLY, default=None, annotation=Optional[Sequence[float]]),
               P("no_limit", P.KEYWORD_ONLY, default=False, annotation=bool),
               P("progress", P.KEYWORD_ONLY, default=None, annotation=_OPTION_TYPES["progress"])]
    return inspect.Signature(params, return_annotation=Front)


design.__doc__ = """The best dampers within the user's limits, as a Pareto front: the design
search of ``thud design`` (NSGA-II), returning a ``Front`` whose numbers are ``thud design
--json``'s for the same inputs and seed. ``design(preset="paper-table3", vary=["mass=20g:120g",
"gap=1cm:6cm"], minimize="spl_max_db", maximize="inclination_cm_s", evaluations=400, seed=1)``.

vary: NAME=FROM:TO over a numeric parameter in its units (a text or a list); choose:
NAME=A,B,C (sphere, plate, or a choice of the design); minimize / maximize: result columns
(spl_max_db, inclination_cm_s, u0_max_m_s, steady_amplitude_m, steady_leq_db, …); require:
COLUMN<=VALUE or COLUMN>=VALUE on a result or a parameter (mass<=60g); over:
"freqs=FROM:TO:N", each result at its worst over the band (a forced design); evaluations: the
budget (default 400); seed (default 0); reference: (V1, V2), the hypervolume's reference point
with two objectives (default: the worst of each among the first designs); no_limit: lift the
work caps; progress: a callable progress(done, total) called with the designs evaluated out of
the budget (at most every 0.1 s, and at the end), or True for a bar on stderr (tqdm if
installed). Every other keyword is the base design's, as for ``simulate``.

Raises ParameterError naming the keyword for bad input. The engine runs without the GIL on
all cores. Ctrl-C stops the search after the batch under way and raises KeyboardInterrupt, as
any long call does; the front found so far is not lost: it is the exception's ``front``, a
``Front`` marked ``partial`` (``except KeyboardInterrupt as e: front = e.front``), as ``thud
design`` keeps it on Ctrl-C. An exception the progress callback raises stops the search the
same way and carries the same ``front``."""
design.__signature__ = _signature()  # type: ignore[attr-defined]
