"""The Datasets of ``thud.bifurcation``, ``thud.continuation`` and a study's ``thud.sweep``: xarray
Datasets that also draw their figure (``to_svg``, ``to_pdf``), the bytes ``thud bifurcation
--svg|--pdf`` (with ``branches=N``: ``--branches N``), ``thud continue --svg|--pdf`` or ``thud
sweep --vary … --svg|--pdf`` (over one or two parameters) writes for the same result.
Each keeps the command line's record it was built from; a Dataset derived from it (``sel``,
``copy``, arithmetic) is data only and has no figure. Imported with xarray."""

from __future__ import annotations

import json
from typing import Any, ClassVar, Dict, Optional, Tuple

import xarray as xr


class _DrawnDataset(xr.Dataset):
    """An xarray Dataset that draws the figure of the record it was built from."""

    __slots__ = ("_thud_record",)
    #: The figure's kind for the native ``_figure`` and the function that made the Dataset.
    _kind: ClassVar[str] = ""
    _made_by: ClassVar[str] = ""
    _command: ClassVar[str] = ""

    def _bytes(self, pdf: bool, size: Optional[Tuple[float, float]], title: bool) -> bytes:
        from . import _thud
        from ._files import look

        record: Optional[Dict[str, Any]] = getattr(self, "_thud_record", None)
        if record is None:
            raise ValueError(f"this Dataset was derived from a {self._kind} result (sel, copy, …) and has no figure; "
                             f"draw the Dataset {self._made_by}() returned")
        data: bytes = _thud._figure(self._kind, json.dumps(record), pdf, **look(size, title))
        return data

    def to_svg(self, path: Any, *, overwrite: bool = False, size: Optional[Tuple[float, float]] = None,
               title: bool = True) -> None:
        """The figure as SVG, the bytes the command line's ``--svg`` writes for the same design,
        values and options. ``size`` (width, height) in px; ``title=False`` leaves the title off;
        an existing file is kept unless ``overwrite``; a symbolic link is never written through."""
        from ._files import write_file

        write_file(path, self._bytes(False, size, title), overwrite)

    def to_pdf(self, path: Any, *, overwrite: bool = False, size: Optional[Tuple[float, float]] = None,
               title: bool = True) -> None:
        """The figure as a one-page PDF (the command line's ``--pdf``); as ``to_svg``."""
        from ._files import write_file

        write_file(path, self._bytes(True, size, title), overwrite)


class BifurcationDataset(_DrawnDataset):
    """A bifurcation diagram as an xarray Dataset (see ``thud._frames.bifurcation_xarray``)
    that draws its figure: ``thud bifurcation --svg|--pdf`` (with ``branches=N`` the continued
    branches over the x(kT) panel, as ``--branches N``)."""

    __slots__ = ()
    _kind = "bifurcation"
    _made_by = "thud.bifurcation"


class ContinuationDataset(_DrawnDataset):
    """A continued branch as an xarray Dataset (see ``thud._results.continuation_xarray``) that
    draws its figure: ``thud continue --svg|--pdf`` over the same range."""

    __slots__ = ()
    _kind = "continuation"
    _made_by = "thud.continuation"


class StudyDataset(_DrawnDataset):
    """A study over one or two parameters as an xarray Dataset (see ``thud._frames.study_xarray``)
    that draws its figure: ``thud sweep --vary … --svg|--pdf`` over the same values."""

    __slots__ = ()
    _kind = "study"
    _made_by = "thud.sweep"


def _drawn(cls: Any, ds: xr.Dataset, record: Dict[str, Any]) -> Any:
    out = cls(ds.data_vars, coords=ds.coords, attrs=ds.attrs)
    object.__setattr__(out, "_thud_record", record)
    return out


def bifurcation_dataset(ds: xr.Dataset, record: Dict[str, Any]) -> BifurcationDataset:
    """``ds`` as a BifurcationDataset drawing ``record`` (the native ``_bifurcation``'s)."""
    out: BifurcationDataset = _drawn(BifurcationDataset, ds, record)
    return out


def continuation_dataset(ds: xr.Dataset, record: Dict[str, Any]) -> ContinuationDataset:
    """``ds`` as a ContinuationDataset drawing ``record`` (the native ``_continuation``'s)."""
    out: ContinuationDataset = _drawn(ContinuationDataset, ds, record)
    return out


def study_dataset(ds: xr.Dataset, record: Dict[str, Any]) -> StudyDataset:
    """``ds`` as a StudyDataset drawing ``record`` (the native ``_study``'s)."""
    out: StudyDataset = _drawn(StudyDataset, ds, record)
    return out
