"""The type stubs (python/thud/__init__.pyi) describe the module as it is: every function, class and attribute,
and every keyword the engine accepts (the engine lists them in its "unknown parameter" message)."""

import ast
import re
from pathlib import Path

import pytest

import thud

STUB = Path(__file__).resolve().parents[1] / "python" / "thud" / "__init__.pyi"
TREE = ast.parse(STUB.read_text(encoding="utf-8"))
OPTIONS = {"pulse": {"preset", "design", "points", "no_limit"},
           "simulate": {"preset", "design", "samples", "no_limit", "ensemble"},
           "sweep": {"preset", "design", "no_limit", "ensemble", "progress"},
           "response": {"preset", "design", "no_limit", "ensemble", "continuation", "progress"}}
#: Design keywords a function refuses although the engine's table has them.
REFUSED = {"response": {"freq"}}


def stub_functions():
    return {n.name: n for n in TREE.body if isinstance(n, ast.FunctionDef)}


def stub_classes():
    return {n.name: n for n in TREE.body if isinstance(n, ast.ClassDef)}


def test_every_public_name_is_in_the_stub_and_exists():
    public = {n for n in dir(thud) if not n.startswith("_")}
    stubbed = set(stub_functions()) | set(stub_classes())
    assert stubbed <= public, stubbed - public
    assert {n for n in public if callable(getattr(thud, n))} <= stubbed


@pytest.mark.parametrize("cls", ["Pulse", "Run", "Ensemble", "Chart", "Response"])
def test_every_attribute_of_a_result_is_in_the_stub(cls):
    node = stub_classes()[cls]
    stubbed = {n.target.id for n in node.body if isinstance(n, ast.AnnAssign)}
    stubbed |= {n.name for n in node.body if isinstance(n, ast.FunctionDef) and not n.name.startswith("_")}
    runtime = {n for n in dir(getattr(thud, cls)) if not n.startswith("_")}
    assert stubbed == runtime


@pytest.mark.parametrize("fn", ["pulse", "simulate", "sweep", "response"])
def test_the_stub_s_keywords_are_the_engine_s(fn):
    with pytest.raises(thud.ParameterError) as info:
        if fn == "sweep":
            thud.sweep([0.04], [0.04], nonesuch=1)
        elif fn == "response":
            thud.response([5.0], nonesuch=1)
        else:
            getattr(thud, fn)(nonesuch=1)
    engine = set(re.search(r"\(one of: ([^)]*)\)", str(info.value)).group(1).split(", "))
    keywords = {a.arg for a in stub_functions()[fn].args.kwonlyargs}
    assert keywords == (engine - REFUSED.get(fn, set())) | OPTIONS[fn]
