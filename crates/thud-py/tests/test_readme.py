"""The documentation's Python examples run as written.

Every ```python block of a page (README.md, every page of the guide under docs/guide, and the
wheel's own README, crates/thud-py/README.md) runs, in order, in one namespace per page, and
`mypy --strict` accepts the guide's Python chapter. Every ```pycon block is a doctest: its
`>>>` lines run and what it shows is compared with what they print, so a changed number fails
here. The install lines name this project's distribution (`thud-damper`), not PyPI's `thud`."""

import doctest
import re
import subprocess
import sys
import textwrap

import pytest

from conftest import REPO, REPORT

README = REPO / "README.md"
PYTHON_PAGE = REPO / "docs" / "guide" / "python.md"
PAGES = [README, REPO / "crates" / "thud-py" / "README.md", *sorted((REPO / "docs" / "guide").rglob("*.md"))]
DISTRIBUTION = "thud-damper"


def blocks(page, lang):
    text = page.read_text(encoding="utf-8")
    return [textwrap.dedent(b) for b in re.findall(rf"^```{lang}\n(.*?)^```", text, re.S | re.M)]


def program(page):
    return "\n".join(blocks(page, "python"))


def test_the_distribution_name_is_the_one_the_docs_install():
    pyproject = (REPO / "crates" / "thud-py" / "pyproject.toml").read_text(encoding="utf-8")
    assert re.search(rf'^name = "{DISTRIBUTION}"$', pyproject, re.M), "pyproject.toml's [project] name"
    readme = README.read_text(encoding="utf-8")
    assert f"pip install {DISTRIBUTION}" in readme
    assert "pip install ./crates/thud-py" in readme
    # No page tells anyone to install PyPI's unrelated `thud`.
    for page in PAGES:
        text = page.read_text(encoding="utf-8")
        assert not re.search(r"pip install '?thud(\[|'|\s|$)", text, re.M), page
    frames = (REPO / "crates" / "thud-py" / "python" / "thud" / "_frames.py").read_text(encoding="utf-8")
    assert f"pip install '{DISTRIBUTION}[frames]'" in frames


def test_the_python_chapter_has_examples_and_installs_with_one_pip_line():
    assert len(blocks(PYTHON_PAGE, "python")) >= 2 and len(blocks(PYTHON_PAGE, "pycon")) >= 2
    first_code = re.search(r"```sh\n(.*?)\n", PYTHON_PAGE.read_text(encoding="utf-8")).group(1)
    assert first_code.split("#")[0].strip() == "pip install ./crates/thud-py"


@pytest.mark.parametrize("page", [p for p in PAGES if blocks(p, "python")], ids=lambda p: p.name)
def test_every_page_s_python_examples_run(page, tmp_path):
    p = subprocess.run([sys.executable, "-c", program(page)], capture_output=True, text=True, cwd=tmp_path,
                       timeout=600)
    assert p.returncode == 0, f"{page}: {p.stderr}"


@pytest.mark.parametrize("page", [p for p in PAGES if blocks(p, "pycon")], ids=lambda p: p.name)
def test_every_page_s_python_sessions_print_what_they_show(page):
    parser = doctest.DocTestParser()
    runner = doctest.DocTestRunner(optionflags=doctest.NORMALIZE_WHITESPACE | doctest.ELLIPSIS)
    globs = {}
    for i, block in enumerate(blocks(page, "pycon")):
        test = parser.get_doctest(block, globs, f"{page.name}[{i}]", str(page), 0)
        runner.run(test, out=lambda s: REPORT.append((f"doctest {page.name}", s.strip()[:300])), clear_globs=False)
        globs = test.globs
    result = runner.summarize(verbose=False)
    assert result.attempted > 0
    assert result.failed == 0, f"{page}: {result.failed} of {result.attempted} examples print something else"


def test_the_doctest_fails_when_an_output_changes():
    """The session check is not vacuous: a block whose shown output is wrong fails."""
    block = ">>> import thud\n>>> round(thud.pulse().spl_db, 2)\n1.0\n"
    test = doctest.DocTestParser().get_doctest(block, {}, "changed", "changed", 0)
    runner = doctest.DocTestRunner()
    runner.run(test, out=lambda s: None)
    assert runner.summarize(verbose=False).failed == 1


def test_mypy_strict_accepts_the_guide_s_examples(tmp_path):
    pytest.importorskip("mypy", reason="mypy is not installed (CI installs it)")
    src = tmp_path / "guide_examples.py"
    src.write_text(program(PYTHON_PAGE), encoding="utf-8")
    p = subprocess.run([sys.executable, "-m", "mypy", "--strict", "--no-incremental", str(src)],
                       capture_output=True, text=True, cwd=tmp_path, timeout=600)
    REPORT.append(("mypy --strict on the guide's Python examples", p.stdout.strip().splitlines()[-1]))
    assert p.returncode == 0, p.stdout + p.stderr


def test_mypy_knows_what_simulate_returns(tmp_path):
    pytest.importorskip("mypy", reason="mypy is not installed (CI installs it)")
    src = tmp_path / "check_types.py"
    src.write_text(textwrap.dedent("""\
        import thud
        run = thud.simulate(mass=0.05)
        reveal_type(run)
        many = thud.simulate(mass=0.05, ensemble=4)
        reveal_type(many)
        reveal_type(thud.simulate_ensemble(4))
        many.impacts
        def some(n: int) -> None:
            reveal_type(thud.simulate(ensemble=n))
        """), encoding="utf-8")
    p = subprocess.run([sys.executable, "-m", "mypy", "--strict", "--no-incremental", str(src)],
                       capture_output=True, text=True, cwd=tmp_path, timeout=600)
    out = p.stdout
    assert 'check_types.py:3: note: Revealed type is "thud.Run"' in out, out
    # ensemble=4 (a literal N > 1) is an Ensemble; an N known only at run time is either.
    assert 'check_types.py:5: note: Revealed type is "thud.Ensemble"' in out, out
    assert 'check_types.py:6: note: Revealed type is "thud.Ensemble"' in out, out
    assert 'check_types.py:7: error: "Ensemble" has no attribute "impacts"' in out, out
    assert 'check_types.py:9: note: Revealed type is "thud.Run | thud.Ensemble"' in out \
        or 'check_types.py:9: note: Revealed type is "Union[thud.Run, thud.Ensemble]"' in out, out
