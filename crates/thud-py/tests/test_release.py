"""The release workflow and what it ships (issue 26 item 3).

.github/workflows/release.yml parses as YAML and builds what the README promises: maturin's
action for wheels on Linux x86_64 and aarch64, macOS and Windows, the sdist, and release
binaries of the command line for the same platforms, packaged by .ci/package-release. That
script runs here too, on the local release build: the archive is an install prefix whose
`man thud` works once unpacked, with the binary, the pages, completions, README and LICENSE."""

import os
import shutil
import subprocess
import tarfile

import pytest

from conftest import REPO, THUD_BIN

WORKFLOW = REPO / ".github" / "workflows" / "release.yml"


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


def test_wheels_for_linux_x86_64_and_aarch64_macos_and_windows_by_maturin(workflow):
    job = workflow["jobs"]["wheels"]
    platforms = job["strategy"]["matrix"]["platform"]
    by_name = {p["name"]: p for p in platforms}
    assert {"linux-x86_64", "linux-aarch64", "windows-x64"} <= set(by_name)
    assert any(p["runner"].startswith("macos") for p in platforms)
    assert by_name["linux-x86_64"]["manylinux"] == by_name["linux-aarch64"]["manylinux"] == "2014"
    build = steps_using(job, "PyO3/maturin-action@")
    assert len(build) == 1
    args = build[0]["with"]["args"]
    manifest = args.split("-m ", 1)[1].split()[0]
    assert (REPO / manifest).is_file(), manifest
    sdist = steps_using(workflow["jobs"]["sdist"], "PyO3/maturin-action@")
    assert sdist[0]["with"]["command"] == "sdist"


def test_binaries_for_the_same_platforms_are_packaged_by_the_script(workflow):
    job = workflow["jobs"]["binaries"]
    targets = {t["target"] for t in job["strategy"]["matrix"]["include"]}
    assert {"x86_64-unknown-linux-gnu", "aarch64-unknown-linux-gnu", "x86_64-pc-windows-msvc"} <= targets
    assert any(t.endswith("apple-darwin") for t in targets)
    runs = "\n".join(s.get("run", "") for s in job["steps"])
    assert "bash .ci/package-release" in runs and (REPO / ".ci" / "package-release").is_file()
    assert "cargo build --release --locked" in runs


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
        return  # man-db is not installed: the layout above is what it needs
    env = {k: v for k, v in os.environ.items() if k != "MANPATH"}
    env["PATH"] = f"{prefix / 'bin'}:/usr/bin:/bin"
    found = subprocess.run(["man", "-w", "thud"], capture_output=True, text=True, env=env, timeout=60)
    assert found.returncode == 0, found.stderr
    assert found.stdout.strip() == str(prefix / "share" / "man" / "man1" / "thud.1")
