"""The Dataset of ``thud.bifurcation``: an xarray Dataset that also draws its figure
(``to_svg``, ``to_pdf``), the bytes ``thud bifurcation --svg|--pdf`` writes for the same
diagram. It keeps the command line's record it was built from; a Dataset derived from it
(``sel``, ``copy``, arithmetic) is data only and has no figure. Imported with xarray."""

from __future__ import annotations

import json
from typing import Any, Dict, Optional, Tuple

import xarray as xr


class BifurcationDataset(xr.Dataset):
    """A bifurcation diagram as an xarray Dataset (see ``thud._frames.bifurcation_xarray``)
    that draws its figure."""

    __slots__ = ("_thud_record",)

    def _bytes(self, pdf: bool, size: Optional[Tuple[float, float]], title: bool) -> bytes:
        from . import _thud
        from ._files import look

        record: Optional[Dict[str, Any]] = getattr(self, "_thud_record", None)
        if record is None:
            raise ValueError("this Dataset was derived from a bifurcation diagram (sel, copy, …) and has no figure; "
                             "draw the Dataset thud.bifurcation() returned")
        data: bytes = _thud._figure("bifurcation", json.dumps(record), pdf, **look(size, title))
        return data

    def to_svg(self, path: Any, *, overwrite: bool = False, size: Optional[Tuple[float, float]] = None,
               title: bool = True) -> None:
        """The bifurcation diagram as SVG, the bytes ``thud bifurcation --svg`` writes for the same
        design, values and options. ``size`` (width, height) in px; ``title=False`` leaves the
        title off; an existing file is kept unless ``overwrite``; a symbolic link is never
        written through."""
        from ._files import write_file

        write_file(path, self._bytes(False, size, title), overwrite)

    def to_pdf(self, path: Any, *, overwrite: bool = False, size: Optional[Tuple[float, float]] = None,
               title: bool = True) -> None:
        """The bifurcation diagram as a one-page PDF (``thud bifurcation --pdf``); as ``to_svg``."""
        from ._files import write_file

        write_file(path, self._bytes(True, size, title), overwrite)


def bifurcation_dataset(ds: xr.Dataset, record: Dict[str, Any]) -> BifurcationDataset:
    """``ds`` as a BifurcationDataset drawing ``record`` (the native ``_bifurcation``'s)."""
    out = BifurcationDataset(ds.data_vars, coords=ds.coords, attrs=ds.attrs)
    object.__setattr__(out, "_thud_record", record)
    return out
