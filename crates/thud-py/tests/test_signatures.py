"""Every function has an explicit keyword signature: inspect.signature
shows the parameters, built from the engine's parameter table, and they are exactly the stub's
and exactly what the engine accepts (its own list in an "unknown parameter" message)."""

import ast
import inspect
import re
from typing import Optional, Union

import pytest

import thud
from test_stubs import stub_functions

FUNCTIONS = ["pulse", "simulate", "simulate_ensemble", "sweep", "response"]
POSITIONAL = {"pulse": [], "simulate": [], "simulate_ensemble": ["runs"], "sweep": ["masses_kg", "gaps_m"],
              "response": ["freqs_hz"]}


def call_with_unknown(fn):
    args = {"sweep": ([0.04], [0.04]), "response": ([5.0],), "simulate_ensemble": (2,)}.get(fn, ())
    with pytest.raises(thud.ParameterError) as info:
        getattr(thud, fn)(*args, nonesuch=1)
    return set(re.search(r"\(one of: ([^)]*)\)", str(info.value)).group(1).split(", "))


@pytest.mark.parametrize("fn", FUNCTIONS)
def test_inspect_signature_lists_every_keyword_the_engine_accepts(fn):
    sig = inspect.signature(getattr(thud, fn))
    kinds = {p.kind for p in sig.parameters.values()}
    assert inspect.Parameter.VAR_KEYWORD not in kinds and inspect.Parameter.VAR_POSITIONAL not in kinds
    positional = [p.name for p in sig.parameters.values() if p.kind is inspect.Parameter.POSITIONAL_OR_KEYWORD]
    assert positional == POSITIONAL[fn]
    keywords = {p.name for p in sig.parameters.values() if p.kind is inspect.Parameter.KEYWORD_ONLY}
    engine = call_with_unknown(fn)
    options = set(thud._thud._parameters()["options"][fn])
    refused = {"response": {"freq"}, "simulate_ensemble": {"ball_position"}}.get(fn, set())
    assert keywords == (engine - refused) | options
    assert "mass" in keywords or fn == "pulse"


@pytest.mark.parametrize("fn", FUNCTIONS)
def test_the_runtime_signature_is_the_stub_s(fn):
    node = stub_functions()[fn]
    args = node.args
    stub = {a.arg: ast.literal_eval(d) for a, d in zip(args.kwonlyargs, args.kw_defaults)}
    sig = inspect.signature(getattr(thud, fn))
    runtime = {p.name: p.default for p in sig.parameters.values() if p.kind is inspect.Parameter.KEYWORD_ONLY}
    assert runtime == stub
    assert [a.arg for a in args.args] == POSITIONAL[fn]


def test_help_shows_the_keywords_and_the_engine_s_docstring():
    text = inspect.getdoc(thud.simulate) or ""
    assert "Eqs 25–27" in text and not text.startswith("simulate(**params)")
    main_mass = inspect.signature(thud.simulate).parameters["main_mass"]
    assert main_mass.default is None and main_mass.annotation == Optional[Union[float, str]]


def test_simulate_ensemble_always_returns_an_ensemble_and_equals_simulate_s():
    one = thud.simulate_ensemble(1, preset="paper-fig9")
    assert isinstance(one, thud.Ensemble) and one.runs == 1
    assert isinstance(thud.simulate(preset="paper-fig9", ensemble=1), thud.Run)
    four = thud.simulate_ensemble(4, preset="paper-fig9")
    assert four.as_dict(json=True) == thud.simulate(preset="paper-fig9", ensemble=4).as_dict(json=True)
    with pytest.raises(thud.ParameterError) as info:
        thud.simulate_ensemble(1, ball_position=0.001)
    assert info.value.param == "ball_position"
    with pytest.raises(thud.ParameterError) as info:
        thud.simulate_ensemble(0)
    assert info.value.param == "runs"


def test_every_public_function_and_method_has_a_signature_without_catch_alls():
    for name in thud.__all__:
        obj = getattr(thud, name)
        # A fit is a dict: the methods it takes unchanged from dict are Python's own (no signature).
        builtin = set().union(*(vars(b) for b in obj.__mro__[1:] if b.__module__ == "builtins")) \
            if isinstance(obj, type) else set()
        targets = [obj] if not isinstance(obj, type) else \
            [getattr(obj, m) for m in dir(obj) if not m.startswith("_") and m not in builtin and callable(getattr(obj, m))]
        if isinstance(obj, type) and issubclass(obj, BaseException):
            continue
        for f in targets:
            params = inspect.signature(f).parameters.values()
            assert all(p.kind not in (p.VAR_KEYWORD, p.VAR_POSITIONAL) for p in params), (name, f)
