"""Shared fixtures: the release binary of the command line (built first: `cargo build
--release`), run with HOME and the XDG folders in a temporary folder so no user config changes
its numbers, and a place to report measurements at the end of the run."""

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]
TARGET = Path(os.environ.get("CARGO_TARGET_DIR", REPO / "target"))
THUD_BIN = Path(os.environ.get("THUD_BIN", TARGET / "release" / "thud"))
EXAMPLES = REPO / "examples" / "python"

#: Measurements printed in the terminal summary (name, value text).
REPORT = []

#: A CI run (CI=true, as CI services set it): CI installs everything the tests need
#: (.ci/run), so there a skipped test fails instead of passing unseen.
IN_CI = os.environ.get("CI", "") not in ("", "false", "0")


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    outcome = yield
    report = outcome.get_result()
    if IN_CI and report.skipped and not hasattr(report, "wasxfail"):
        reason = report.longrepr[2] if isinstance(report.longrepr, tuple) else str(report.longrepr)
        report.outcome = "failed"
        report.longrepr = f"skipped in CI (CI={os.environ['CI']}), where .ci/run installs what it needs: {reason}"


@pytest.fixture(scope="session")
def home(tmp_path_factory):
    """An empty HOME for the command line: no config file, no saved designs."""
    return tmp_path_factory.mktemp("home")


@pytest.fixture(scope="session")
def cli_env(home):
    env = dict(os.environ)
    env.update(HOME=str(home), XDG_CONFIG_HOME=str(home / "config"), XDG_DATA_HOME=str(home / "data"))
    env.pop("XDG_CONFIG_DIRS", None)
    return env


@pytest.fixture(scope="session")
def cli(cli_env):
    """Runs `thud ARGS`; returns (exit code, stdout, stderr)."""
    if not THUD_BIN.is_file():
        pytest.fail(f"{THUD_BIN} is missing: build it first with `cargo build --release`")

    def run(*args):
        p = subprocess.run([str(THUD_BIN), *args], capture_output=True, text=True, env=cli_env, timeout=120)
        return p.returncode, p.stdout, p.stderr

    return run


@pytest.fixture(scope="session")
def cli_json(cli):
    """Runs `thud ARGS --json` and parses its output."""

    def run(*args):
        code, out, err = cli(*args, "--json")
        assert code == 0, err
        return json.loads(out)

    return run


@pytest.fixture(scope="session")
def python_env(cli_env):
    """The environment for example scripts: the test's Python and the CLI's clean HOME."""
    return cli_env


def run_example(env, *args, timeout=300):
    """Runs an example script with this Python; returns the completed process."""
    p = subprocess.run([sys.executable, *map(str, args)], capture_output=True, text=True, env=env, timeout=timeout)
    assert p.returncode == 0, f"{args}: exit {p.returncode}\n{p.stdout}\n{p.stderr}"
    return p


def pytest_terminal_summary(terminalreporter):
    if REPORT:
        terminalreporter.section("thud measurements")
        for name, value in REPORT:
            terminalreporter.write_line(f"{name}: {value}")
