"""``to_svg``, ``to_pdf`` and ``to_wav`` of the native results (Pulse, Run, Chart, Response): the
file ``thud export svg|pdf|wav`` writes for the result's impact, design and axes, byte for byte."""

from typing import Any, Dict, Optional, Tuple

from . import _thud
from ._files import PathLike, look, render, write_file

Size = Optional[Tuple[float, float]]


def _refuse(param: str, message: str) -> Exception:
    """A ``ParameterError`` naming ``param``, as the native module raises them."""
    err = _thud.ParameterError(message)
    err.param = param
    return err


def _run_figure(run: Any, pdf: bool, size: Size, title: bool) -> bytes:
    return render("history", run.design, pdf, points=len(run.history["t_s"]), **look(size, title))


def run_to_svg(self: Any, path: PathLike, *, overwrite: bool = False, size: Size = None, title: bool = True) -> None:
    """The time history with and without the damper as SVG: ``thud export svg history``
    of this design with ``--points`` the run's samples. ``size`` (width, height) in px;
    ``title=False`` leaves the title off; an existing file is kept unless ``overwrite``."""
    write_file(path, _run_figure(self, False, size, title), overwrite)


def run_to_pdf(self: Any, path: PathLike, *, overwrite: bool = False, size: Size = None, title: bool = True) -> None:
    """The time history as a one-page PDF (``thud export pdf history``); as ``to_svg``."""
    write_file(path, _run_figure(self, True, size, title), overwrite)


def run_to_wav(self: Any, path: PathLike, *, overwrite: bool = False, full_scale: float = 20.0,
               format: str = "pcm16") -> None:
    """The damper's sound at the observer over the whole run as WAV (``thud export wav``): 48 kHz
    mono, each sample the mean pressure over its interval / ``full_scale`` Pa; ``format``
    "pcm16", "pcm24" or "float". An existing file is kept unless ``overwrite``."""
    write_file(path, render("wav", self.design, False, full_scale=full_scale, format=format), overwrite)


def _chart_figure(chart: Any, figure: str, pdf: bool, size: Size, title: bool) -> bytes:
    if figure not in ("chart", "fig17"):
        raise _refuse("figure", f"invalid figure: '{figure}'; expected chart or fig17")
    if chart.runs > 1:
        if figure != "chart":
            raise _refuse("figure", f"invalid figure: '{figure}'; a chart of ensembles draws its ensemble chart "
                          "(figure=\"chart\"), as `thud sweep --ensemble N --svg`")
        data: bytes = chart._ensemble_figure(pdf, **look(size, title))
        return data
    return render(figure, chart.design, pdf, masses_kg=[float(m) for m in chart.masses_kg],
                  gaps_m=[float(g) for g in chart.gaps_m], **look(size, title))


def chart_to_svg(self: Any, path: PathLike, *, figure: str = "chart", overwrite: bool = False, size: Size = None,
                 title: bool = True) -> None:
    """The design chart as SVG, ``thud export svg chart`` (``figure="fig17"``: the Fig 17 zone
    chart) over this chart's masses and gaps; of a chart of ensembles (``ensemble=N``), the
    ensemble chart of ``thud sweep --ensemble N --svg``. An existing file is kept unless
    ``overwrite``."""
    write_file(path, _chart_figure(self, figure, False, size, title), overwrite)


def chart_to_pdf(self: Any, path: PathLike, *, figure: str = "chart", overwrite: bool = False, size: Size = None,
                 title: bool = True) -> None:
    """The design chart as a one-page PDF (``thud export pdf chart|fig17``); as ``to_svg``."""
    write_file(path, _chart_figure(self, figure, True, size, title), overwrite)


def _response_figure(r: Any, pdf: bool, size: Size, title: bool) -> bytes:
    if r.runs > 1:
        raise _refuse("ensemble", "invalid ensemble: the response figure draws one trajectory a frequency; "
                      "an ensemble's response has no figure")
    freqs = [float(f) for f in r.sweeps[0]["freq_hz"]]
    options: Dict[str, Any] = look(size, title)
    return render("response", r.design, pdf, freqs_hz=freqs, continuation=bool(r.continuation), **options)


def response_to_svg(self: Any, path: PathLike, *, overwrite: bool = False, size: Size = None,
                    title: bool = True) -> None:
    """The frequency response as SVG (``thud export svg response`` over this response's
    frequencies); an existing file is kept unless ``overwrite``."""
    write_file(path, _response_figure(self, False, size, title), overwrite)


def response_to_pdf(self: Any, path: PathLike, *, overwrite: bool = False, size: Size = None,
                    title: bool = True) -> None:
    """The frequency response as a one-page PDF (``thud export pdf response``); as ``to_svg``."""
    write_file(path, _response_figure(self, True, size, title), overwrite)


def pulse_to_svg(self: Any, path: PathLike, *, overwrite: bool = False, size: Size = None,
                 title: bool = True) -> None:
    """The pulse's pressure against time after the direct arrival as SVG: ``thud export svg
    pulse`` with this pulse's flags and ``--points`` its samples. ``size`` (width, height) in px;
    ``title=False`` leaves the title off; an existing file is kept unless ``overwrite``."""
    write_file(path, self._file("svg", **look(size, title)), overwrite)


def pulse_to_pdf(self: Any, path: PathLike, *, overwrite: bool = False, size: Size = None,
                 title: bool = True) -> None:
    """The pulse as a one-page PDF (``thud export pdf pulse``); as ``to_svg``."""
    write_file(path, self._file("pdf", **look(size, title)), overwrite)


def pulse_to_wav(self: Any, path: PathLike, *, overwrite: bool = False, full_scale: float = 20.0,
                 format: str = "pcm16") -> None:
    """The pulse's sound at the observer as WAV (``thud export wav pulse``): 48 kHz mono from the
    contact's start to 0.1 s after the last wave, each sample the mean pressure over its interval
    / ``full_scale`` Pa; ``format`` "pcm16", "pcm24" or "float". An existing file is kept unless
    ``overwrite``."""
    write_file(path, self._file("wav", full_scale=full_scale, format=format), overwrite)


def attach() -> None:
    """The methods on the native classes."""
    for cls, methods in ((_thud.Pulse, {"to_svg": pulse_to_svg, "to_pdf": pulse_to_pdf, "to_wav": pulse_to_wav}),
                         (_thud.Run, {"to_svg": run_to_svg, "to_pdf": run_to_pdf, "to_wav": run_to_wav}),
                         (_thud.Chart, {"to_svg": chart_to_svg, "to_pdf": chart_to_pdf}),
                         (_thud.Response, {"to_svg": response_to_svg, "to_pdf": response_to_pdf})):
        for name, fn in methods.items():
            setattr(cls, name, fn)
