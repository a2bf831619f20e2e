"""The release workflow and what it ships.

.github/workflows/release.yml parses as YAML and releases exactly what CI builds and tests:
.ci/run builds and tests the command line on its host (Linux x86_64) and the Python module as
one manylinux2014 abi3 wheel with maturin; the workflow builds maturin's wheel and the sdist, and
the release binary, for that platform alone, packaged by .ci/package-release. That script runs
here too, on the local release build: the archive is an install prefix whose `man thud` works
once unpacked, with the binary, the pages, completions, README and LICENSE."""

import os
import re
import shutil
import subprocess
import tarfile

import pytest

from conftest import REPO, THUD_BIN

WORKFLOW = REPO / ".github" / "workflows" / "release.yml"
CI = REPO / ".ci" / "run"


def ci_builds():
    """What .ci/run builds: the host's target triple (its `cargo test --release` and the binary
    the tests run) and the manylinux policy of its one wheel build (`--compatibility`)."""
    host = subprocess.run(["rustc", "-vV"], capture_output=True, text=True, check=True, timeout=60).stdout
    triple = re.search(r"^host: (\S+)$", host, re.M).group(1)
    run = CI.read_text(encoding="utf-8")
    assert "cargo test --release" in run
    policies = re.findall(r"maturin build [^\n]*--compatibility manylinux(\d+)", run)
    assert len(policies) == 1, policies
    return triple, policies[0]


@pytest.fixture(scope="module")
def workflow():
    yaml = pytest.importorskip("yaml", reason="PyYAML is not installed (CI installs it)")
    doc = yaml.safe_load(WORKFLOW.read_text(encoding="utf-8"))
    assert isinstance(doc, dict), doc
    return doc


def steps_using(job, action):
    return [s for s in job["steps"] if s.get("uses", "").startswith(action)]


def test_the_workflow_runs_on_version_tags(workflow):
    # PyYAML reads the key `on` as True (YAML 1.1).
    on = workflow.get("on", workflow.get(True))
    assert on["push"]["tags"] == ["v*"]
    assert {"wheels", "sdist", "binaries", "release", "pypi"} <= set(workflow["jobs"])


def test_the_wheels_are_the_one_wheel_ci_builds_by_maturin(workflow):
    triple, manylinux = ci_builds()
    job = workflow["jobs"]["wheels"]
    platforms = job["strategy"]["matrix"]["platform"]
    arch, _, os_name = triple.partition("-unknown-")
    assert os_name == "linux-gnu", f"CI runs on {triple}; the release is built for what CI builds"
    assert platforms == [
        {"name": f"linux-{arch}", "runner": "ubuntu-latest", "target": arch, "manylinux": manylinux}
    ], platforms
    build = steps_using(job, "PyO3/maturin-action@")
    assert len(build) == 1
    assert build[0]["with"]["target"] == "${{ matrix.platform.target }}"
    assert build[0]["with"]["manylinux"] == "${{ matrix.platform.manylinux }}"
    args = build[0]["with"]["args"]
    manifest = args.split("-m ", 1)[1].split()[0]
    assert (REPO / manifest).is_file(), manifest
    sdist = steps_using(workflow["jobs"]["sdist"], "PyO3/maturin-action@")
    assert sdist[0]["with"]["command"] == "sdist"
    assert "maturin sdist" in CI.read_text(encoding="utf-8")


def test_the_binaries_are_the_one_ci_builds_packaged_by_the_script(workflow):
    triple, _ = ci_builds()
    job = workflow["jobs"]["binaries"]
    targets = [t["target"] for t in job["strategy"]["matrix"]["include"]]
    assert targets == [triple], targets
    runs = "\n".join(s.get("run", "") for s in job["steps"])
    assert "bash .ci/package-release" in runs and (REPO / ".ci" / "package-release").is_file()
    assert "cargo build --release --locked" in runs


def test_the_package_promises_only_the_platform_ci_builds():
    pyproject = (REPO / "crates" / "thud-py" / "pyproject.toml").read_text(encoding="utf-8")
    systems = re.findall(r'"Operating System :: ([^"]+)"', pyproject)
    assert systems == ["POSIX :: Linux"], systems
    readme = (REPO / "README.md").read_text(encoding="utf-8")
    install = readme.split("## Install", 1)[1].split("\n## ", 1)[0]
    assert "no Windows zip" in install and ".zip" not in install.replace("no Windows zip", "")


def test_the_release_archive_is_a_prefix_where_man_finds_thud(tmp_path):
    if not THUD_BIN.is_file():
        pytest.fail(f"{THUD_BIN} is missing: build it first with `cargo build --release`")
    out = tmp_path / "dist"
    p = subprocess.run(["bash", str(REPO / ".ci" / "package-release"), "x86_64-unknown-linux-gnu", str(THUD_BIN),
                        str(out)], capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stderr
    archive = next(out.glob("thud-*-x86_64-unknown-linux-gnu.tar.gz"))
    with tarfile.open(archive) as t:
        names = {n.split("/", 1)[1] for n in t.getnames() if "/" in n}
        t.extractall(tmp_path / "unpacked", filter="data")
    for want in ("bin/thud", "share/man/man1/thud.1", "share/man/man1/thud-sweep.1", "share/doc/thud/README.md",
                 "share/doc/thud/LICENSE", "share/bash-completion/completions/thud",
                 "share/zsh/site-functions/_thud", "share/fish/vendor_completions.d/thud.fish"):
        assert want in names, (want, sorted(names))
    prefix = next((tmp_path / "unpacked").iterdir())
    if shutil.which("man") is None:
        pytest.skip("man (man-db) is not installed: only the layout `man` needs was checked")
    env = {k: v for k, v in os.environ.items() if k != "MANPATH"}
    env["PATH"] = f"{prefix / 'bin'}:/usr/bin:/bin"
    found = subprocess.run(["man", "-w", "thud"], capture_output=True, text=True, env=env, timeout=60)
    assert found.returncode == 0, found.stderr
    assert found.stdout.strip() == str(prefix / "share" / "man" / "man1" / "thud.1")
