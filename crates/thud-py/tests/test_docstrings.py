"""help(thud.simulate) and the other functions document every keyword the engine accepts, each
on one line with its row's help and range: the "Keywords" section is generated from the
engine's parameter table, so a row missing from it fails here."""

import pydoc

import pytest

import thud
from test_signatures import call_with_unknown

FUNCTIONS = ["pulse", "simulate", "simulate_ensemble", "sweep", "response"]


@pytest.mark.parametrize("fn", FUNCTIONS)
def test_help_documents_every_keyword_with_its_help_and_range(fn):
    text = pydoc.render_doc(getattr(thud, fn), renderer=pydoc.plaintext)
    lines = [line.strip() for line in text.splitlines()]
    table = thud._thud._parameters()
    rows = {r["name"]: r for r in table["pulse" if fn == "pulse" else "design"]}
    refused = set(table["refused"].get(fn, []))
    # The engine's own list of what it accepts (its "unknown parameter" message).
    accepted = call_with_unknown(fn) - refused
    assert accepted and accepted <= set(rows)
    for name in accepted:
        row = rows[name]
        documented = [line for line in lines if line.startswith(f"{name}: ")]
        assert len(documented) == 1, (fn, name, documented)
        line = documented[0]
        assert row["help"] in line, (fn, name, line)
        if row["range"] is not None:
            assert row["range"] in line, (fn, name, line)
        for choice in row.get("choices", []):
            assert f'"{choice}"' in line, (fn, name, line)
    for name in refused:
        assert not any(line.startswith(f"{name}: ") for line in lines), (fn, name)


def test_the_design_keywords_carry_the_command_line_s_help_and_ranges():
    text = pydoc.render_doc(thud.simulate, renderer=pydoc.plaintext)
    assert "main_mass: Main mass M (kg); 0.001 to 1e6 kg" in text
    assert "force: Amplitude F0 of a harmonic force" in text and "(alias force_amplitude)" in text
    assert 'solver: Solver ("event" | "newmark")' in text
