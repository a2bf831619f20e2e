"""The README's Python examples run as written, and `mypy --strict` accepts them (items 3 and
the acceptance of issue 19): every ```python block of the "From Python" section, in order, in
one namespace."""

import re
import subprocess
import sys
import textwrap

import pytest

from conftest import REPO, REPORT

README = REPO / "README.md"


def python_blocks():
    text = README.read_text(encoding="utf-8")
    section = text.split("\n## From Python\n", 1)[1].split("\n## ", 1)[0]
    return [textwrap.dedent(b) for b in re.findall(r"```python\n(.*?)```", section, re.S)]


def program():
    return "\n".join(python_blocks())


def test_the_readme_has_python_examples_and_installs_with_one_pip_line():
    blocks = python_blocks()
    assert len(blocks) >= 4
    text = README.read_text(encoding="utf-8")
    section = text.split("\n## From Python\n", 1)[1]
    first_code = re.search(r"```sh\n(.*?)\n", section).group(1)
    assert first_code.split("#")[0].strip() == "pip install ./crates/thud-py"


def test_the_readme_s_python_examples_run(tmp_path):
    p = subprocess.run([sys.executable, "-c", program()], capture_output=True, text=True, cwd=tmp_path, timeout=600)
    assert p.returncode == 0, p.stderr


def test_mypy_strict_accepts_the_readme_s_examples(tmp_path):
    pytest.importorskip("mypy", reason="mypy is not installed (CI installs it)")
    src = tmp_path / "readme_examples.py"
    src.write_text(program(), encoding="utf-8")
    p = subprocess.run([sys.executable, "-m", "mypy", "--strict", "--no-incremental", str(src)],
                       capture_output=True, text=True, cwd=tmp_path, timeout=600)
    REPORT.append(("mypy --strict on the README's Python examples", p.stdout.strip().splitlines()[-1]))
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
        """), encoding="utf-8")
    p = subprocess.run([sys.executable, "-m", "mypy", "--strict", "--no-incremental", str(src)],
                       capture_output=True, text=True, cwd=tmp_path, timeout=600)
    out = p.stdout
    assert 'check_types.py:3: note: Revealed type is "thud.Run"' in out, out
    assert 'check_types.py:5: note: Revealed type is "thud.Run | thud.Ensemble"' in out \
        or 'check_types.py:5: note: Revealed type is "Union[thud.Run, thud.Ensemble]"' in out, out
    assert 'check_types.py:6: note: Revealed type is "thud.Ensemble"' in out, out
    # An Ensemble has no impacts: the checker says so for the union.
    assert re.search(r'check_types.py:7: error: Item "Ensemble" of .* has no attribute "impacts"', out), out
