"""Figures and sound from Python: each result's ``to_svg``/``to_pdf``/``to_wav`` writes the very
bytes ``thud export svg|pdf|wav`` writes for the same design and axes, and writes them as thud
writes every file (never over a file without ``overwrite=True``, never through a symbolic link,
no temporary file left behind)."""

import os

import pytest

import thud

#: A short free decay: the default design for 0.3 s.
RUN_KW = dict(duration=0.3)
RUN = ["--duration", "0.3"]


def exported(cli, tmp_path, *args):
    """The bytes `thud export ARGS --out FILE` writes."""
    out = tmp_path / f"cli-{len(os.listdir(tmp_path))}.bin"
    code, _, err = cli("export", *args, "--out", str(out))
    assert code == 0, err
    return out.read_bytes()


def written(tmp_path, write):
    """The bytes a `to_…` method writes to a new file."""
    path = tmp_path / f"py-{len(os.listdir(tmp_path))}.bin"
    write(path)
    return path.read_bytes()


def test_a_run_draws_its_history_and_plays_its_sound_as_the_cli_exports_them(cli, tmp_path):
    run = thud.simulate(samples=501, **RUN_KW)
    svg = written(tmp_path, run.to_svg)
    assert svg.startswith(b"<svg") or b"<svg" in svg[:200]
    assert svg == exported(cli, tmp_path, "svg", "history", "--points", "501", *RUN)
    assert written(tmp_path, run.to_pdf) == exported(cli, tmp_path, "pdf", "history", "--points", "501", *RUN)
    wav = written(tmp_path, run.to_wav)
    assert wav[:4] == b"RIFF" and wav == exported(cli, tmp_path, "wav", *RUN)
    loud = written(tmp_path, lambda p: run.to_wav(p, full_scale=5, format="float"))
    assert loud == exported(cli, tmp_path, "wav", "--full-scale", "5", "--format", "float", *RUN)
    assert loud != wav
    small = written(tmp_path, lambda p: run.to_svg(p, size=(600, 400), title=False))
    assert small == exported(cli, tmp_path, "svg", "history", "--points", "501", "--size", "600x400", "--no-title",
                             *RUN)


def test_a_pulse_draws_its_waveform_and_plays_its_sound_as_the_cli_exports_them(cli, tmp_path):
    p = thud.pulse(u0=2, theta=30, main_mass=3, source="quadrupole", points=500)
    args = ["--u0", "2", "--theta", "30", "--main-mass", "3", "--source", "quadrupole"]
    svg = written(tmp_path, p.to_svg)
    assert b"U0 2 m/s" in svg and b"quadrupole" in svg
    assert svg == exported(cli, tmp_path, "svg", "pulse", "--points", "500", *args)
    pdf = written(tmp_path, lambda path: p.to_pdf(path, size=(600, 400), title=False))
    assert pdf.startswith(b"%PDF")
    assert pdf == exported(cli, tmp_path, "pdf", "pulse", "--points", "500", "--size", "600x400", "--no-title", *args)
    wav = written(tmp_path, p.to_wav)
    assert wav[:4] == b"RIFF" and wav == exported(cli, tmp_path, "wav", "pulse", *args)
    assert any(wav[44:]), "the pulse is heard"
    loud = written(tmp_path, lambda path: p.to_wav(path, full_scale=0.5, format="pcm24"))
    assert loud == exported(cli, tmp_path, "wav", "pulse", "--full-scale", "0.5", "--format", "pcm24", *args)
    # Another impact draws another figure; an unpickled pulse draws its original's.
    import pickle
    assert written(tmp_path, pickle.loads(pickle.dumps(p)).to_svg) == svg
    assert written(tmp_path, thud.pulse(u0=2, points=500).to_svg) != svg
    physical = thud.pulse(model="physical", sphere="steel", r=0.5)
    assert written(tmp_path, physical.to_svg) == exported(cli, tmp_path, "svg", "pulse", "--model", "physical",
                                                          "--sphere", "steel", "--r", "0.5")


def test_a_chart_draws_its_zones_and_fig17_as_the_cli_exports_them(cli, tmp_path):
    chart = thud.sweep("30g:60g:3", "2cm:4cm:2", **RUN_KW)
    axes = ["--masses", "30g:60g:3", "--gaps", "2cm:4cm:2", *RUN]
    assert written(tmp_path, chart.to_svg) == exported(cli, tmp_path, "svg", "chart", *axes)
    fig17 = written(tmp_path, lambda p: chart.to_pdf(p, figure="fig17"))
    assert fig17.startswith(b"%PDF") and fig17 == exported(cli, tmp_path, "pdf", "fig17", *axes)
    with pytest.raises(thud.ParameterError) as info:
        chart.to_svg(tmp_path / "never.svg", figure="polar")  # type: ignore[arg-type]
    assert info.value.param == "figure" and "polar" in str(info.value)
    assert not (tmp_path / "never.svg").exists()


def test_a_chart_of_ensembles_draws_the_ensemble_chart_of_sweep(cli, tmp_path):
    chart = thud.sweep("30g:60g:2", "2cm:4cm:2", ensemble=3, **RUN_KW)
    args = ["sweep", "--masses", "30g:60g:2", "--gaps", "2cm:4cm:2", "--ensemble", "3", *RUN, "--out",
            str(tmp_path / "table.txt")]
    code, _, err = cli(*args, "--svg", str(tmp_path / "cli.svg"), "--pdf", str(tmp_path / "cli.pdf"))
    assert code == 0, err
    svg = written(tmp_path, chart.to_svg)
    assert b"Ensemble chart: 3 runs a cell" in svg and svg == (tmp_path / "cli.svg").read_bytes()
    assert written(tmp_path, chart.to_pdf) == (tmp_path / "cli.pdf").read_bytes()
    assert svg != written(tmp_path, thud.sweep("30g:60g:2", "2cm:4cm:2", **RUN_KW).to_svg)
    with pytest.raises(thud.ParameterError) as info:
        chart.to_svg(tmp_path / "never.svg", figure="fig17")
    assert info.value.param == "figure" and "ensemble" in str(info.value)


def test_a_response_draws_its_figure_as_the_cli_exports_it(cli, tmp_path):
    r = thud.response("4.6Hz:5.4Hz:3", force="1N", periods=4, duration=1)
    args = ["--freqs", "4.6Hz:5.4Hz:3", "--force-amplitude", "1N", "--periods", "4", "--duration", "1"]
    assert written(tmp_path, r.to_svg) == exported(cli, tmp_path, "svg", "response", *args)


def test_restitution_draws_fig13_as_the_cli_exports_it(cli, tmp_path):
    r = thud.restitution("10g:40g:4", u0=1.2)
    args = ["--masses", "10g:40g:4", "--u0", "1.2"]
    assert written(tmp_path, r.to_svg) == exported(cli, tmp_path, "svg", "restitution", *args)
    assert written(tmp_path, r.to_pdf) == exported(cli, tmp_path, "pdf", "restitution", *args)


def test_a_figure_is_never_written_over_a_file_or_through_a_link(tmp_path):
    run = thud.simulate(samples=101, **RUN_KW)
    path = tmp_path / "fig.svg"
    path.write_bytes(b"mine")
    with pytest.raises(FileExistsError) as info:
        run.to_svg(path)
    assert "overwrite=True" in str(info.value) and path.read_bytes() == b"mine"
    run.to_svg(path, overwrite=True)
    assert path.read_bytes().lstrip().startswith(b"<")
    # A link planted where the figure goes: refused, its target untouched, even with overwrite.
    victim = tmp_path / "victim.txt"
    victim.write_bytes(b"keep")
    link = tmp_path / "link.svg"
    link.symlink_to(victim)
    for overwrite in (False, True):
        with pytest.raises(FileExistsError) as info:
            run.to_svg(link, overwrite=overwrite)
        assert "symbolic link" in str(info.value)
    assert victim.read_bytes() == b"keep" and link.is_symlink()
    # A folder is never replaced.
    (tmp_path / "dir.svg").mkdir()
    with pytest.raises(FileExistsError):
        run.to_svg(tmp_path / "dir.svg", overwrite=True)
    # No temporary file is left behind, on success or refusal.
    assert sorted(p.name for p in tmp_path.iterdir()) == ["dir.svg", "fig.svg", "link.svg", "victim.txt"]


def test_bad_figure_options_name_their_keyword(tmp_path):
    run = thud.simulate(samples=101, **RUN_KW)
    with pytest.raises(thud.ParameterError) as info:
        run.to_svg(tmp_path / "a.svg", size=(10, 10))
    assert info.value.param == "size" and "480" in str(info.value)
    with pytest.raises(thud.ParameterError) as info:
        run.to_wav(tmp_path / "a.wav", format="mp3")
    assert info.value.param == "format"
    with pytest.raises(thud.ParameterError) as info:
        run.to_wav(tmp_path / "a.wav", full_scale=-1)
    assert info.value.param == "full_scale"
    assert list(tmp_path.iterdir()) == []


def test_basins_and_impact_maps_draw_what_their_commands_draw(cli, tmp_path):
    b = thud.basins(3, (-0.5, 0.5), preset="forced-rattle", transient=20, periods=4)
    args = ["--preset", "forced-rattle", "--grid", "3", "--w0", "-0.5:0.5", "--transient", "20", "--periods", "4"]
    for method, flag in ((b.to_svg, "--svg"), (b.to_pdf, "--pdf")):
        out = tmp_path / f"basins{flag}"
        code, _, err = cli("basins", *args, flag, str(out))
        assert code == 0, err
        assert written(tmp_path, method) == out.read_bytes()
    m = thud.impact_map(preset="forced-rattle", transient=20, periods=4)
    out = tmp_path / "map.svg"
    code, _, err = cli("impact-map", "--preset", "forced-rattle", "--transient", "20", "--periods", "4", "--svg",
                       str(out))
    assert code == 0, err
    assert written(tmp_path, m.to_svg) == out.read_bytes()


def test_a_bifurcation_diagram_draws_what_thud_bifurcation_draws(cli, tmp_path):
    # 7, 7.5 and 8 Hz: the same three values from the command line's FROM:TO:N and from here.
    kw = dict(preset="forced-rattle", transient=20, periods=4)
    args = ["bifurcation", "--preset", "forced-rattle", "--transient", "20", "--periods", "4"]
    for continuation in (False, True):
        ds = thud.bifurcation(freq=[7.0, 7.5, 8.0], continuation=continuation, **kw)
        extra = ["--vary", "f=7Hz:8Hz:3"] + (["--continuation"] if continuation else [])
        for method, flag in ((ds.to_svg, "--svg"), (ds.to_pdf, "--pdf")):
            out = tmp_path / f"bif-{continuation}{flag}"
            code, _, err = cli(*args, *extra, flag, str(out))
            assert code == 0, err
            assert written(tmp_path, method) == out.read_bytes()
    # The title names what varies and over which range.
    svg = written(tmp_path, ds.to_svg).decode()
    assert "over freq 7–8 Hz" in svg
    # A Dataset derived from the diagram is data only: no figure of the whole drawn for a part.
    with pytest.raises(ValueError, match="derived"):
        ds.isel(point=[0]).to_svg(tmp_path / "part.svg")
    assert not (tmp_path / "part.svg").exists()
    # Pickled and back, it draws the same figure.
    import pickle

    again = pickle.loads(pickle.dumps(ds))
    assert written(tmp_path, again.to_svg) == written(tmp_path, ds.to_svg)


def test_a_continued_branch_draws_what_thud_continue_draws(cli, tmp_path):
    ds = thud.continuation(preset="forced-rattle", freq=(5.5, 5.6))
    for method, flag in ((ds.to_svg, "--svg"), (ds.to_pdf, "--pdf")):
        out = tmp_path / f"continue{flag}"
        code, _, err = cli("continue", "--preset", "forced-rattle", "--vary", "f=5.5:5.6", flag, str(out))
        assert code == 0, err
        assert written(tmp_path, method) == out.read_bytes()
    svg = written(tmp_path, ds.to_svg).decode()
    assert "Orbits continued over freq 5.5–5.6 Hz" in svg
    with pytest.raises(ValueError, match="derived"):
        ds.isel(point=[0]).to_svg(tmp_path / "part.svg")
    assert not (tmp_path / "part.svg").exists()


def test_a_bifurcation_with_branches_draws_what_thud_bifurcation_branches_draws(cli, tmp_path):
    kw = dict(preset="forced-rattle", transient=20, periods=4)
    args = ["bifurcation", "--preset", "forced-rattle", "--transient", "20", "--periods", "4", "--vary", "f=7Hz:8Hz:3"]
    plain = thud.bifurcation(freq=[7.0, 7.5, 8.0], **kw)
    ds = thud.bifurcation(freq=[7.0, 7.5, 8.0], branches=2, **kw)
    for method, flag in ((ds.to_svg, "--svg"), (ds.to_pdf, "--pdf")):
        out = tmp_path / f"branches{flag}"
        code, _, err = cli(*args, "--branches", "2", flag, str(out))
        assert code == 0, err
        assert written(tmp_path, method) == out.read_bytes()
    # The branches are drawn: not the plain diagram's figure.
    assert written(tmp_path, ds.to_svg) != written(tmp_path, plain.to_svg)
    for bad in (1, 1001, 2.5, True, "two"):
        with pytest.raises(thud.ParameterError, match="branches") as info:
            thud.bifurcation(freq=[7.0, 8.0], branches=bad, **kw)
        assert info.value.param == "branches"


def test_a_study_draws_what_thud_sweep_vary_draws(cli, tmp_path):
    """A study over one or two parameters draws the bytes of ``thud sweep --vary … --svg|--pdf``
    for the same values; over three it is refused, naming why."""
    two = thud.sweep(v0=[1.0, 2.0], c1=[10.0, 20.0], duration=0.5)
    one = thud.sweep(v0=[1.0, 1.5, 2.0], duration=0.5)
    cases = [(two, ["--vary", "v0=1:2:2", "--vary", "c1=10:20:2"]), (one, ["--vary", "v0=1:2:3"])]
    for ds, vary in cases:
        for method, flag in ((ds.to_svg, "--svg"), (ds.to_pdf, "--pdf")):
            out = tmp_path / f"study-{len(vary)}{flag}"
            code, _, err = cli("sweep", *vary, "--duration", "0.5", "--csv", flag, str(out))
            assert code == 0, err
            assert written(tmp_path, method) == out.read_bytes()
    svg = written(tmp_path, two.to_svg).decode()
    assert "Study over v0 1–2 m/s × c1 10–20 N·s/m" in svg
    assert written(tmp_path, one.to_svg) != written(tmp_path, two.to_svg)
    with pytest.raises(ValueError, match="derived"):
        two.isel(v0_m_s=[0]).to_svg(tmp_path / "part.svg")
    three = thud.sweep(v0=[1.0, 2.0], c1=[10.0, 20.0], gap=[0.03, 0.04], duration=0.5)
    with pytest.raises(thud.ParameterError, match="one or two parameters, not 3"):
        three.to_svg(tmp_path / "three.svg")
    assert not (tmp_path / "three.svg").exists()
