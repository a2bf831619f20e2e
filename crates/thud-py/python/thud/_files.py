"""Figures and sound of a result written to a file: the bytes ``thud export svg|pdf|wav`` writes
for the same design (the native ``_render``), written as thud writes every file: never over an
existing file unless ``overwrite=True``, never through a symbolic link, and never half-written
(a temporary file in the same folder, then renamed into place)."""

import errno
import json
import os
import stat
import tempfile
from typing import Any, Dict, Optional, Tuple, Union

from . import _thud

PathLike = Union[str, "os.PathLike[str]"]


def write_file(path: PathLike, data: bytes, overwrite: bool = False) -> None:
    """``data`` to ``path``: atomically, refusing an existing file unless ``overwrite`` (and then
    only a regular file), and never through a symbolic link at ``path``."""
    target = os.fspath(path)
    try:
        st: Optional[os.stat_result] = os.lstat(target)
    except FileNotFoundError:
        st = None
    if st is not None:
        if stat.S_ISLNK(st.st_mode):
            raise FileExistsError(errno.EEXIST, "is a symbolic link; thud never writes through one", target)
        if not stat.S_ISREG(st.st_mode):
            raise FileExistsError(errno.EEXIST, "exists and is not a regular file", target)
        if not overwrite:
            raise FileExistsError(errno.EEXIST, "exists; pass overwrite=True to replace it", target)
    folder = os.path.dirname(os.path.abspath(target))
    fd, tmp = tempfile.mkstemp(dir=folder, prefix=".thud-", suffix=".tmp")
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
            f.flush()
            os.fsync(f.fileno())
        # mkstemp's file is private (0600); a written figure gets the umask's usual mode.
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)
        if overwrite:
            # Replaces the name itself (a link planted meanwhile is replaced, never followed).
            os.replace(tmp, target)
        else:
            # A hard link never replaces an existing name: a file that appeared meanwhile stays.
            try:
                os.link(tmp, target)
            except FileExistsError:
                raise FileExistsError(errno.EEXIST, "exists; pass overwrite=True to replace it", target) from None
            os.unlink(tmp)
    except BaseException:
        try:
            os.unlink(tmp)
        except FileNotFoundError:
            pass
        raise


def render(kind: str, design: Dict[str, Any], pdf: bool = False, **options: Any) -> bytes:
    """The bytes of ``thud export svg|pdf|wav KIND`` for ``design`` (a result's design dict)."""
    data: bytes = _thud._render(kind, json.dumps(design), pdf, **options)
    return data


def look(size: Optional[Tuple[float, float]], title: bool) -> Dict[str, Any]:
    """The figure options every ``to_svg``/``to_pdf`` takes."""
    return {"size": None if size is None else (float(size[0]), float(size[1])), "title": bool(title)}
