"""The wheel installs on real clusters: one abi3 wheel tagged
manylinux2014 (manylinux_2_17), needing no glibc symbol newer than 2.17, stripped (no symbol
table, no debug info), under 5 MB; and an sdist that holds everything a build needs.

CI builds the wheel once (`maturin build --release --zig --compatibility manylinux2014`),
installs it for the other tests and passes its path in THUD_WHEEL; without it this test builds
the wheel itself (needs maturin and ziglang)."""

import os
import re
import struct
import subprocess
import sys
import tarfile
import zipfile
from pathlib import Path

import pytest

from conftest import REPO, REPORT, THUD_BIN

CRATE = REPO / "crates" / "thud-py"
MAX_BYTES = 5 * 1024 * 1024


def maturin(*args, out):
    pytest.importorskip("maturin", reason="maturin is not installed")
    cmd = [sys.executable, "-m", "maturin", *args, "-m", str(CRATE / "Cargo.toml"), "-o", str(out)]
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=1800)
    assert p.returncode == 0, p.stderr[-3000:]


@pytest.fixture(scope="module")
def wheel(tmp_path_factory):
    given = os.environ.get("THUD_WHEEL")
    if given:
        return Path(given)
    pytest.importorskip("ziglang", reason="ziglang is not installed (pip install ziglang)")
    out = tmp_path_factory.mktemp("wheel")
    maturin("build", "--release", "--zig", "--compatibility", "manylinux2014", out=out)
    return next(out.glob("*.whl"))


def elf_sections(data):
    """The section names of a 64-bit little-endian ELF file."""
    assert data[:4] == b"\x7fELF" and data[4] == 2 and data[5] == 1
    shoff, = struct.unpack_from("<Q", data, 0x28)
    shentsize, shnum, shstrndx = struct.unpack_from("<HHH", data, 0x3A)
    def header(i):
        return struct.unpack_from("<IIQQQQ", data, shoff + i * shentsize)
    strtab_off = header(shstrndx)[4]
    names = []
    for i in range(shnum):
        name_off = header(i)[0]
        end = data.index(b"\0", strtab_off + name_off)
        names.append(data[strtab_off + name_off:end].decode())
    return names


def test_the_wheel_is_abi3_manylinux2014_stripped_and_small(wheel):
    size = wheel.stat().st_size
    REPORT.append(("wheel", f"{wheel.name}: {size / 1e6:.2f} MB"))
    assert size < MAX_BYTES, f"{wheel.name} is {size} bytes"
    name = wheel.name
    assert re.match(r"thud_damper-[\d.]+-cp39-abi3-.*\.whl$", name), name
    assert "manylinux_2_17_x86_64" in name and "manylinux2014_x86_64" in name, name
    with zipfile.ZipFile(wheel) as z:
        files = z.namelist()
        meta = z.read(next(f for f in files if f.endswith(".dist-info/WHEEL"))).decode()
        tags = {line.split(": ", 1)[1] for line in meta.splitlines() if line.startswith("Tag: ")}
        so = next(f for f in files if re.match(r"thud/_thud\..*so$", f))
        lib = z.read(so)
    assert "cp39-abi3-manylinux_2_17_x86_64" in tags and "cp39-abi3-manylinux2014_x86_64" in tags, tags
    for f in ("thud/__init__.py", "thud/__init__.pyi", "thud/py.typed", "thud/_frames.py", "thud/_wrap.py"):
        assert f in files, (f, files)
    sections = elf_sections(lib)
    assert not [s for s in sections if s.startswith(".debug")], sections
    assert ".symtab" not in sections, "the library is not stripped"
    glibc = {tuple(map(int, v.split(b"."))) for v in re.findall(rb"GLIBC_(\d+\.\d+(?:\.\d+)?)", lib)}
    assert glibc and max(glibc) <= (2, 17), sorted(glibc)


def metadata_fields(text):
    """The header fields of a METADATA / PKG-INFO file: name → list of values."""
    head = text.split("\n\n", 1)[0]
    fields = {}
    for line in head.splitlines():
        if ": " in line and not line.startswith(" "):
            k, v = line.split(": ", 1)
            fields.setdefault(k, []).append(v)
    return fields, text.split("\n\n", 1)[1] if "\n\n" in text else ""


def check_metadata(text):
    """A registry page that is not blank: name, summary, licence and its file, URLs,
    classifiers, Requires-Python and the README as the description."""
    fields, body = metadata_fields(text)
    assert fields["Name"] == ["thud-damper"], fields.get("Name")
    assert fields["Summary"][0].startswith("Design single-unit impact dampers")
    assert fields.get("License-Expression") == ["MIT"], fields
    assert "LICENSE" in fields.get("License-File", []), fields
    assert fields["Requires-Python"] == [">=3.9"]
    urls = dict(u.split(", ", 1) for u in fields.get("Project-URL", []))
    assert {"Homepage", "Documentation", "Repository", "Changelog"} <= set(urls), urls
    assert any(c.startswith("Topic :: Scientific/Engineering") for c in fields["Classifier"])
    assert "Programming Language :: Rust" in fields["Classifier"]
    assert fields["Description-Content-Type"][0].startswith("text/markdown")
    assert "pip install thud-damper" in body, body[:400]


def test_the_wheel_s_metadata_fills_a_registry_page(wheel):
    with zipfile.ZipFile(wheel) as z:
        files = z.namelist()
        meta = z.read(next(f for f in files if f.endswith(".dist-info/METADATA"))).decode()
        assert any(f.endswith(".dist-info/licenses/LICENSE") or f.endswith(".dist-info/LICENSE") for f in files), files
    check_metadata(meta)


def test_the_sdist_holds_everything_its_build_reads(tmp_path):
    """`maturin sdist` makes an archive that builds: besides the module, the engine and the lock
    file, every file a crate in it compiles in (include_str!/include_bytes!, e.g. the presets)
    resolves inside the archive, and it carries LICENSE, README and its metadata. (Building it
    into a wheel is what CI does: .ci/run builds the wheel from this very sdist.)"""
    maturin("sdist", out=tmp_path)
    sdist = next(tmp_path.glob("thud_damper-*.tar.gz"))
    with tarfile.open(sdist) as t:
        members = {m.name.split("/", 1)[1]: m for m in t.getmembers() if "/" in m.name}
        names = list(members)
        for want in ("pyproject.toml", "Cargo.lock", "LICENSE", "README.md", "python/thud/__init__.py",
                     "python/thud/__init__.pyi", "python/thud/py.typed", "crates/thud-core/src/lib.rs",
                     "crates/thud-presets/presets/default.toml"):
            assert any(n == want or n.endswith("/" + want) for n in names), (want, names[:40])
        included = 0
        for name in names:
            if not name.endswith(".rs"):
                continue
            source = t.extractfile(members[name]).read().decode()
            for rel in re.findall(r'include_(?:str|bytes)!\(\s*"([^"]+)"\s*\)', source):
                target = os.path.normpath(os.path.join(os.path.dirname(name), rel))
                assert target in members, f"{name} compiles in {rel}, which the sdist lacks ({target})"
                included += 1
        assert included >= 8, included  # the presets at least
        check_metadata(t.extractfile(members["PKG-INFO"]).read().decode())


def test_the_release_binary_carries_no_debug_info():
    """The release profile ships no debug info (the `profiling` profile keeps it for
    benchmarks): the command line that `cargo build --release` made has no .debug sections."""
    if not THUD_BIN.is_file():
        pytest.fail(f"{THUD_BIN} is missing: build it first with `cargo build --release`")
    sections = elf_sections(THUD_BIN.read_bytes())
    assert ".text" in sections and not [s for s in sections if s.startswith(".debug")], sections
