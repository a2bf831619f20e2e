"""Every Python block of the guide (docs/guide/*.md) runs, and `mypy --strict` accepts it
against the type stubs: the blocks of one page in order, as one script (a later block uses
what an earlier one made)."""

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]
GUIDE = REPO / "docs" / "guide"
BLOCK = re.compile(r"^```python\n(.*?)^```", re.S | re.M)


def pages():
    return sorted(p for p in GUIDE.glob("*.md") if BLOCK.search(p.read_text(encoding="utf-8")))


def script(page: Path) -> str:
    return "\n".join(BLOCK.findall(page.read_text(encoding="utf-8")))


def test_the_guide_has_python_blocks():
    names = {p.name for p in pages()}
    assert {"python.md", "studies.md", "dynamics.md", "fit.md"} <= names, names


@pytest.mark.parametrize("page", pages(), ids=lambda p: p.name)
def test_every_python_block_of_the_guide_runs(page, tmp_path, cli_env):
    f = tmp_path / f"{page.stem}.py"
    f.write_text(script(page), encoding="utf-8")
    p = subprocess.run([sys.executable, str(f)], capture_output=True, text=True, env=cli_env, cwd=tmp_path,
                       timeout=600)
    assert p.returncode == 0, p.stderr[-3000:]


def test_mypy_strict_accepts_every_python_block_of_the_guide(tmp_path):
    pytest.importorskip("mypy")
    files = []
    for page in pages():
        f = tmp_path / f"guide_{page.stem}.py"
        f.write_text(script(page), encoding="utf-8")
        files.append(str(f))
    env = dict(os.environ, MYPY_CACHE_DIR=str(tmp_path / ".mypy_cache"))
    p = subprocess.run([sys.executable, "-m", "mypy", "--strict", "--no-incremental", *files], capture_output=True,
                       text=True, env=env, cwd=tmp_path, timeout=600)
    assert p.returncode == 0, p.stdout[-3000:] + p.stderr[-1000:]
    assert "Success" in p.stdout, p.stdout
