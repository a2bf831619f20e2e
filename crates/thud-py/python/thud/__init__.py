"""thud — design single-unit impact dampers from Python, on the engine of the `thud` app.

pulse(**params) -> Pulse, simulate(**params) -> Run (an Ensemble with ensemble=N > 1),
simulate_ensemble(runs, **params) -> Ensemble, sweep(masses_kg, gaps_m, **params) -> Chart,
response(freqs_hz=None, **params) -> Response.

Parameters are the command line's long flags as keywords (``--main-mass`` → ``main_mass=``):
a plain number in SI units (angles in degrees, levels in dB, inclinations in cm/s), or a
string with a unit ("40.5g", "4cm"). Bad input raises ``ParameterError`` (a ``ValueError``)
naming the parameter. Every result pickles, has ``as_dict(json=True)`` and tables
(``Run.impacts_frame()``, ``Chart.to_dataframe()``, ``Chart.to_xarray()`` with pandas /
xarray installed). Long sweeps take ``progress=True`` (or a callable); Ctrl-C stops them.

This package is a thin layer over the native module ``thud._thud``: the functions below have
explicit keyword signatures (``inspect.signature``, ``help``) built at import from the engine's
own parameter table, so they list exactly the keywords the engine accepts.
"""

import json as _json
from typing import Any as _Any
from typing import Dict as _Dict
from typing import List as _List
from typing import Union as _Union
from typing import TypedDict as _TypedDict

from . import _frames, _thud
from ._thud import (
    Chart,
    Ensemble,
    ParameterError,
    Pulse,
    Response,
    Run,
    __version__,
    axis,
    limits,
    paper_ids,
    presets,
    ranges,
    schema,
)
from ._design import Designer, Front, design
from ._results import Basins, DamperFit, ImpactMap, Orbit, Restitution, StructureFit
from ._results import _restore_record
from ._results import continuation_xarray as _continuation_xarray
from ._figures import attach as _attach_figures
from ._wrap import document as _document
from ._wrap import with_progress as _progress

__all__ = [
    "Basins",
    "Chart",
    "DamperFit",
    "Designer",
    "Ensemble",
    "Front",
    "ImpactMap",
    "PaperColumn",
    "PaperTable",
    "LimitCap",
    "LimitRange",
    "Limits",
    "Orbit",
    "ParameterError",
    "Pulse",
    "Response",
    "Restitution",
    "Run",
    "StructureFit",
    "axis",
    "basins",
    "bifurcation",
    "continuation",
    "design",
    "fit_damper",
    "fit_structure",
    "impact_map",
    "limits",
    "orbit",
    "paper",
    "paper_ids",
    "presets",
    "pulse",
    "ranges",
    "response",
    "restitution",
    "schema",
    "simulate",
    "simulate_ensemble",
    "sweep",
]


class LimitRange(_TypedDict):
    """A parameter's range in ``limits()["ranges"]``: param as the command line's flag."""

    max: float
    min: float
    param: str
    reason: str
    unit: str
    what: str


class LimitCap(_TypedDict):
    """A work cap in ``limits()["caps"]`` and ``["solver_caps"]``."""

    basis: str
    max: float
    what: str


class Limits(_TypedDict):
    """``thud limits --json``, key for key."""

    caps: _List[LimitCap]
    orbit_seed_impacts_max: int
    orbit_transient_periods_max: int
    ranges: _List[LimitRange]
    settle_periods_max: int
    solver_caps: _List[LimitCap]


class PaperColumn(_TypedDict):
    """A column of a paper table: its key in each row, its heading as printed."""

    key: str
    label: str


class PaperTable(_TypedDict, total=False):
    """A table or figure of the paper, as ``thud paper ID --json`` (``summary`` only for some)."""

    id: str
    title: str
    notes: _List[str]
    columns: _List[PaperColumn]
    rows: _List[_Dict[str, _Any]]
    summary: _Dict[str, _Dict[str, _Any]]


def paper(id: str) -> PaperTable:
    """A table or figure of the paper reproduced beside the paper's numbers: the dict of
    ``thud paper ID --json``, key for key (``paper_ids()`` lists the ids, table1 … fig17)."""
    table: PaperTable = _json.loads(_thud._paper(id))
    return table


def _restore(kind: str, state: str) -> _Any:
    """A result again from its pickled state (what every result's ``__reduce__`` names)."""
    if kind in ("Orbit", "ImpactMap", "Basins", "Restitution"):
        return _restore_record(kind, state)
    return _thud._restore(kind, state)


def pulse(**params: _Any) -> Pulse:
    return _thud.pulse(**params)


def simulate(**params: _Any) -> _Union[Run, Ensemble]:
    return _thud.simulate(**params)


def simulate_ensemble(runs: _Union[int, str], **params: _Any) -> Ensemble:
    return _thud.simulate_ensemble(runs, **params)


def _is_axis(value: _Any) -> bool:
    """Whether a keyword's value is a list of values to vary (a sequence or an array, not text)."""
    if isinstance(value, (str, bytes)) or value is None:
        return False
    try:
        iter(value)
    except TypeError:
        return False
    return True


def _axes(params: _Dict[str, _Any]) -> _List[_Any]:
    """The varied keywords of a call (each a sequence of numbers), taken out of `params`."""
    names = [k for k, v in params.items() if _is_axis(v)]
    axes = []
    for k in names:
        v = params.pop(k)
        axes.append((k, v.tolist() if hasattr(v, "tolist") else list(v)))
    return axes


def sweep(masses_kg: _Any = None, gaps_m: _Any = None, **params: _Any) -> _Any:
    if masses_kg is None and gaps_m is None:
        # A study over any parameters, the keywords to vary given as sequences:
        # sweep(v0=np.linspace(1, 3, 5), c1=[10, 20]) → xarray (mass × gap too: mass=[…], gap=[…]).
        axes = _axes(params)
        record = _json.loads(_thud._study(axes, **_progress(params, "sweep")))
        return _frames.study_xarray(record)
    return _thud.sweep(masses_kg, gaps_m, **_progress(params, "sweep"))


def bifurcation(**params: _Any) -> _Any:
    """The bifurcation diagram of a forced design over one parameter given as a sequence
    (``thud bifurcation --vary``): ``bifurcation(freq=np.linspace(3, 8, 200), force=3,
    preset="forced-rattle")`` → an xarray Dataset (``thud._frames.bifurcation_xarray``) that
    draws its diagram (``ds.to_svg(path)``, ``ds.to_pdf(path)``: ``thud bifurcation --svg|--pdf``).
    Options: transient (periods run before sampling, default 200), periods (sampled, default
    100), continuation (rising then falling, each value from the last one's end state),
    branches (N: the periodic orbits' branches continued from N seed values, drawn over the
    figure's x(kT) panel, as ``--branches N``), progress, no_limit; every other keyword is the
    design's, as for ``simulate``."""
    axes = _axes(params)
    if len(axes) != 1:
        raise ParameterError(f"invalid vary: bifurcation varies exactly one parameter given as a sequence, not {len(axes)}")
    (name, values), = axes
    record = _json.loads(_thud._bifurcation(name, values, **_progress(params, "bifurcation")))
    return _frames.bifurcation_xarray(record)


def orbit(**params: _Any) -> Orbit:
    """The periodic orbit of a forced design found by shooting (Newton on the stroboscopic
    map), stable or not, as ``thud orbit --json``: ``orbit(preset="forced-rattle")``,
    ``orbit(gap=0.02, force=2, freq=6, symmetric=True)``. Options: period (the orbit's period
    in forcing periods, 1 to 16; default the one the design's motion repeats with), symmetric
    (look for x(t + T/2) = −x(t)), guess ((x, v, z, zdot) in m, m/s, m, m/s at the force's
    phase 0, to start Newton's method from instead of the design's motion); every other
    keyword is the design's, as for ``simulate``."""
    return Orbit(_json.loads(_thud._orbit(**params)))


def continuation(**params: _Any) -> _Any:
    """The family of periodic orbits of a forced design continued over one parameter
    (pseudo-arclength, through folds and along unstable parts), as ``thud continue --json``:
    the parameter given as (FROM, TO), e.g. ``continuation(freq=(3, 8), force=3,
    preset="forced-rattle")`` → an xarray Dataset on the dimension point (the value, orbit,
    stability, largest |λ|, amplitude and state at phase 0) with the special points (fold,
    period doubling, Neimark–Sacker, branch point, grazing) on the dimension special. A varied
    frequency supplies the design's. The Dataset draws its figure (``ds.to_svg(path)``,
    ``ds.to_pdf(path)``: ``thud continue --svg|--pdf``, byte for byte). Options: period,
    symmetric (as for ``orbit``)."""
    axes = _axes(params)
    if len(axes) != 1:
        raise ParameterError(f"invalid vary: continuation varies exactly one parameter given as (FROM, TO), not {len(axes)}")
    (name, values), = axes
    return _continuation_xarray(_json.loads(_thud._continuation(name, values, **params)))


def impact_map(**params: _Any) -> ImpactMap:
    """The impact map of a forced design, as ``thud impact-map --json``: its stroboscopic
    samples and every impact over ``periods`` forcing periods after ``transient`` ones
    (default 200), and the orbit's type. Options: transient, no_limit; every other keyword is
    the design's, as for ``simulate``."""
    return ImpactMap(_json.loads(_thud._impact_map(**params)))


def basins(grid: _Union[int, str] = 20, w0: _Any = (-1.0, 1.0), **params: _Any) -> Basins:
    """The basins of attraction of a forced design over the ball's start, as ``thud basins
    --json``: ``grid`` offsets y0 across the clearance × ``grid`` velocities w0 over ``w0``
    (FROM, TO) in m/s (default −1 to 1); each start's attractor and amplitude. Options:
    transient, no_limit; every other keyword is the design's (not ball_position or
    ball_velocity: the basins set the ball's start)."""
    try:
        lo, hi = w0
    except (TypeError, ValueError):
        e = ParameterError(f"invalid w0: expected (FROM, TO) in m/s, e.g. (-1, 1), not {w0!r}")
        e.param = "w0"  # type: ignore[attr-defined]
        raise e from None
    return Basins(_json.loads(_thud._basins(grid, (lo, hi), **params)))


def restitution(masses_kg: _Any = "5g:100g:20", u0: _Union[float, str] = 1.4, target: _Any = None,
                **params: _Any) -> Restitution:
    """The restitution R of one isolated contact at approach speed ``u0`` (m/s) against the
    impact mass, as ``thud restitution`` (Fig 13): masses_kg a sequence (kg) or "FROM:TO:N"
    text (default "5g:100g:20"); with ``target`` (a wanted R in (0, 1]) also the c1 that gives
    it for each mass. Every other keyword is the design's."""
    return Restitution(_json.loads(_thud._restitution(masses_kg, u0, target, **params)))


def response(freqs_hz: _Any = None, **params: _Any) -> Response:
    return _thud.response(freqs_hz, **_progress(params, "response"))


def fit_structure(t_s: _Any, x: _Any, *, main_mass: _Union[float, str], quantity: str = "x") -> StructureFit:
    """The structure alone, struck once: f_n, ζ, K and C with standard errors from a measured
    free decay, as ``thud fit structure --json`` (a ``StructureFit``, a dict: f_n_hz, zeta, k_n_m, c_n_s_m, each
    with ``_stderr``, residual_rms, converged, …). ``t_s``: times (s, increasing, any spacing);
    ``x``: the signal as ``quantity`` "x" (m), "v" (m/s) or "a" (m/s²), offset and drift
    allowed; ``main_mass``: M (kg, or e.g. "2kg"). Bad data raises ParameterError."""
    return StructureFit(_thud.fit_structure(t_s, x, main_mass=main_mass, quantity=quantity))


def fit_damper(t_s: _Any, x: _Any, **params: _Any) -> DamperFit:
    return DamperFit(_thud.fit_damper(t_s, x, **params))


_document(globals())
_attach_figures()
