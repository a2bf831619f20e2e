"""thud.design (the design search of `thud design`) and its ask/tell form thud.Designer.

- thud.design gives the very record `thud design --json` prints for the same inputs and seed;
  its tables are `--csv`'s; it pickles to an equal object.
- Every front design, run again with thud.simulate, gives exactly its objectives.
- A Designer told the results thud.simulate gives reaches exactly thud.design's front.
- Bad input names the keyword; the GIL is released; progress hears the evaluations; Ctrl-C
  stops a search and its KeyboardInterrupt carries the front found so far, marked partial.
"""

import ast
import io
import json
import os
import pickle
import signal
import threading
import time

import pytest

import thud
from conftest import REPORT
from test_stubs import STUB

PAPER = dict(preset="paper-table3", vary=["mass=20g:120g", "gap=1cm:6cm"], minimize="spl_max_db",
             maximize="inclination_cm_s")
PAPER_FLAGS = ["--preset", "paper-table3", "--vary", "mass=20g:120g", "--vary", "gap=1cm:6cm",
               "--minimize", "spl_max_db", "--maximize", "inclination_cm_s"]
#: A problem with a choice, a constraint on a parameter and one on a result.
CHOICE = dict(preset="paper-table3", vary="mass=20g:120g", choose="sphere=steel,acrylic,nylon",
              minimize="spl_max_db", maximize="inclination_cm_s", require=["mass<=80g", "spl_max_db<=104"])
CHOICE_FLAGS = ["--preset", "paper-table3", "--vary", "mass=20g:120g", "--choose", "sphere=steel,acrylic,nylon",
                "--minimize", "spl_max_db", "--maximize", "inclination_cm_s", "--require", "mass<=80g",
                "--require", "spl_max_db<=104"]


def cli_record(cli, flags, *more):
    code, out, err = cli("design", *flags, *more, "--json")
    assert code == 0, err
    return json.loads(out)


@pytest.mark.parametrize("seed", [1, 2])
def test_design_is_the_command_line_s_record(cli, seed):
    front = thud.design(**PAPER, evaluations=400, seed=seed, reference=(106, 0))
    want = cli_record(cli, PAPER_FLAGS, "--evaluations", "400", "--seed", str(seed), "--reference", "106,0")
    assert front.as_dict() == want
    assert len(front) == len(want["front"]) > 5
    assert front.hypervolume == want["hypervolume"] and front.evaluations == 400 and not front.partial


def test_a_choice_and_constraints_are_the_command_line_s_too(cli):
    front = thud.design(**CHOICE, evaluations=80, seed=3)
    want = cli_record(cli, CHOICE_FLAGS, "--evaluations", "80", "--seed", "3")
    assert front.as_dict() == want
    for d in front.designs:
        assert d["variables"]["mass_kg"] <= 0.08
        assert all(m >= 0 for m in d["margins"].values())
        assert d["variables"]["sphere"] in ("steel", "acrylic", "nylon")


def test_the_tables_are_the_csv_s(cli):
    pd = pytest.importorskip("pandas")
    xr = pytest.importorskip("xarray")
    front = thud.design(**CHOICE, evaluations=80, seed=3)
    code, out, err = cli("design", *CHOICE_FLAGS, "--evaluations", "80", "--seed", "3", "--csv")
    assert code == 0, err
    want = pd.read_csv(io.StringIO(out))
    df = front.to_dataframe()
    assert list(df.columns) == list(want.columns)
    assert list(df.columns) == ["index", "mass_kg", "sphere", "spl_max_db", "inclination_cm_s",
                                "margin_mass_le", "margin_spl_max_db_le"]
    pd.testing.assert_frame_equal(df.reset_index(drop=True), want, check_dtype=False, rtol=0, atol=0)
    ds = front.to_xarray()
    assert isinstance(ds, xr.Dataset) and ds.sizes["design"] == len(front)
    assert ds["mass_kg"].attrs["units"] == "kg"
    assert list(ds["spl_max_db"].values) == list(df["spl_max_db"])
    assert ds.attrs["seed"] == 3 and ds.attrs["budget"] == 80


def test_a_front_pickles_to_an_equal_object():
    front = thud.design(**CHOICE, evaluations=40, seed=5)
    again = pickle.loads(pickle.dumps(front))
    assert again == front and again is not front
    assert again.keywords(0) == front.keywords(0)
    assert front != thud.design(**CHOICE, evaluations=40, seed=6)


def test_every_front_design_run_again_gives_its_objectives():
    front = thud.design(**CHOICE, evaluations=80, seed=3)
    assert len(front) >= 2
    for k, d in enumerate(front.designs):
        run = thud.simulate(preset="paper-table3", **front.keywords(k))
        assert run.spl_max_db == d["objectives"]["spl_max_db"]
        assert run.inclination_cm_s == d["objectives"]["inclination_cm_s"]
        assert d["margins"]["spl_max_db<=104"] == 104 - run.spl_max_db


def drive(designer, n, reverse=False):
    """Runs an ask/tell search to its end, evaluating each point with thud.simulate."""
    rounds = 0
    while not designer.done:
        xs = designer.ask(n)
        runs = [thud.simulate(**designer.base, **x, samples=2) for x in xs]
        if reverse:
            xs, runs = xs[::-1], runs[::-1]
        designer.tell(xs, runs)
        rounds += 1
    return rounds


@pytest.mark.parametrize("n", [7, 1000])
def test_ask_tell_evaluated_by_simulate_reaches_design_s_front(n):
    want = thud.design(**PAPER, evaluations=200, seed=4)
    d = thud.Designer(**PAPER, evaluations=200, seed=4)
    assert d.columns == ["spl_max_db", "inclination_cm_s"]
    assert d.base == {"preset": "paper-table3"}
    assert not d.done and d.result().partial
    rounds = drive(d, n, reverse=True)
    got = d.result()
    assert got == want and not got.partial
    assert rounds > 200 // 1000 + 1
    assert d.ask(5) == []


def test_ask_tell_with_results_as_mappings_and_failures():
    d = thud.Designer(**CHOICE, evaluations=40, seed=3)
    assert d.columns == ["spl_max_db", "inclination_cm_s"]
    xs = d.ask(3)
    assert len(xs) == 3 and d.outstanding == 3
    assert set(xs[0]) == {"mass", "sphere"}
    with pytest.raises(thud.ParameterError) as e:
        d.tell(xs[:1], [{"spl_max_db": 90.0}])
    assert "inclination_cm_s" in str(e.value) and e.value.param == "results"
    with pytest.raises(thud.ParameterError) as e:
        d.tell([{"mass": 0.0123456, "sphere": "steel"}], [{"spl_max_db": 90.0, "inclination_cm_s": 1.0}])
    assert e.value.param == "xs" and "not asked" in str(e.value)
    d.tell(xs, [{"spl_max_db": 90.0, "inclination_cm_s": None}, RuntimeError("the node died"), "no licence"])
    assert d.outstanding == 0
    with pytest.raises(thud.ParameterError):
        d.tell(xs[:1], [{"spl_max_db": 90.0, "inclination_cm_s": 1.0}])


@pytest.mark.parametrize("bad, param", [
    (dict(vary="nope=1:2"), "vary"),
    (dict(vary="mass=120g:20g"), "vary"),
    (dict(minimize="spl"), "minimize"),
    (dict(maximize=3), "maximize"),
    (dict(require="spl_max_db=100"), "require"),
    (dict(choose="sphere=steel,unobtainium"), "choose"),
    (dict(over="4Hz:5Hz:3"), "over"),
    (dict(over="freqs=4Hz:5Hz:3"), "over"),
    (dict(evaluations=0), "evaluations"),
    (dict(seed=-1), "seed"),
    (dict(seed="many"), "seed"),
    (dict(reference=(106, 0, 1)), "reference"),
    (dict(reference=(106, float("nan"))), "reference"),
    (dict(minimize="steady_leq_db"), "force"),
    (dict(mass="lots"), "mass"),
])
def test_bad_input_names_the_keyword(bad, param):
    args = dict(PAPER, evaluations=20)
    if "minimize" in bad or "maximize" in bad:
        args.pop("minimize"), args.pop("maximize")
        args.update(bad)
        args.setdefault("maximize", "inclination_cm_s")
    else:
        args.update(bad)
    for make in (thud.design, thud.Designer):
        with pytest.raises(thud.ParameterError) as e:
            make(**args)
        assert e.value.param == param, str(e.value)
        assert "\n" not in str(e.value)


#: The command line's forced-band problem: worst steady amplitude against worst Leq over
#: 4.5, 5 and 5.5 Hz (around the structure's 5.03 Hz), the ball at most 80 g.
BAND = dict(force=2, freq=5, duration=3, vary=["mass=20g:120g", "gap=1cm:6cm"], over="freqs=4.5Hz:5.5Hz:3",
            minimize=["steady_amplitude_m", "steady_leq_db"], require="mass<=80g")


def test_ask_tell_over_a_band_told_simulate_s_runs_reaches_design_s_front(cli):
    want = thud.design(**BAND, evaluations=24, seed=2)
    flags = ["--force-amplitude", "2", "--freq", "5", "--duration", "3", "--vary", "mass=20g:120g", "--vary",
             "gap=1cm:6cm", "--over", "freqs=4.5Hz:5.5Hz:3", "--minimize", "steady_amplitude_m", "--minimize",
             "steady_leq_db", "--require", "mass<=80g"]
    assert want.as_dict() == cli_record(cli, flags, "--evaluations", "24", "--seed", "2")
    d = thud.Designer(**BAND, evaluations=24, seed=2)
    assert d.band_hz == [4.5, 5.0, 5.5] == want.band_hz
    assert d.columns == ["steady_amplitude_m", "steady_leq_db"]
    while not d.done:
        xs = d.ask(5)
        runs = [[thud.simulate(**kw, samples=2) for kw in d.runs(x)] for x in xs]
        assert all([kw["freq"] for kw in d.runs(x)] == d.band_hz for x in xs)
        d.tell(xs[::-1], runs[::-1])
    got = d.result()
    assert len(got) > 0 and not got.partial
    assert got == want
    # A point of a band told one run is refused naming the results, and stays asked.
    d = thud.Designer(**BAND, evaluations=24, seed=2)
    x = d.ask(1)
    with pytest.raises(thud.ParameterError) as e:
        d.tell(x, [thud.simulate(**d.runs(x[0])[0], samples=2)])
    assert e.value.param == "results" and "3 results" in str(e.value)
    assert d.outstanding == 1


def test_no_variable_or_no_objective_is_refused():
    with pytest.raises(thud.ParameterError) as e:
        thud.design(preset="paper-table3", minimize="spl_max_db")
    assert e.value.param == "vary"
    with pytest.raises(thud.ParameterError) as e:
        thud.design(preset="paper-table3", vary="mass=20g:120g")
    assert e.value.param == "minimize"


def test_an_infeasible_problem_says_which_constraint_binds():
    front = thud.design(**dict(PAPER, require=["mass<=60g", "spl_max_db<=10"]), evaluations=24, seed=1)
    assert len(front) == 0
    assert front.binding is not None and "spl_max_db<=10 binds" in front.binding


def test_python_runs_while_a_search_works():
    counts = {"during": 0}
    done = threading.Event()
    worker = threading.Thread(target=lambda: (thud.design(**PAPER, evaluations=400, seed=1, duration=6), done.set()))
    t0 = time.perf_counter()
    worker.start()
    while not done.is_set():
        counts["during"] += 1
    worker.join()
    took = time.perf_counter() - t0
    REPORT.append(("thud.design, 400 evaluations of 6 s runs, while a Python loop counts", f"{took:.2f} s"))
    # Were the GIL held for the search, the loop would stop once the worker took it.
    assert counts["during"] > 1000 * took, (counts, took)


def test_ctrl_c_stops_a_search():
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    t0 = time.perf_counter()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt) as e:
            thud.design(**PAPER, evaluations=5000, seed=1, duration=200, no_limit=True)
    finally:
        timer.cancel()
    elapsed = time.perf_counter() - t0
    REPORT.append(("Ctrl-C stopped thud.design after", f"{elapsed:.2f} s"))
    assert elapsed < 5, f"the search went on for {elapsed:.1f} s after Ctrl-C"
    # The front found so far rides on the interrupt, marked partial, within the budget.
    front = e.value.front
    assert isinstance(front, thud.Front) and front.partial
    assert front.evaluations < front.budget == 5000
    assert not hasattr(e.value, "_thud_front")


def test_progress_hears_the_evaluations_out_of_the_budget():
    heard = []
    front = thud.design(**PAPER, evaluations=120, seed=2, progress=lambda done, total: heard.append((done, total)))
    assert heard and all(total == 120 for _, total in heard)
    done = [d for d, _ in heard]
    assert done == sorted(done) and done[-1] == front.evaluations
    assert not front.partial
    with pytest.raises(thud.ParameterError) as bad:
        thud.design(**PAPER, evaluations=20, progress="yes")
    assert bad.value.param == "progress"
    with pytest.raises(thud.ParameterError) as bad:
        thud.Designer(**PAPER, evaluations=20, progress=print)
    assert bad.value.param == "progress"


def test_a_search_stopped_keeps_the_front_of_what_it_evaluated():
    """A progress callback that raises KeyboardInterrupt (Ctrl-C in a notebook) stops the
    search after the batch under way; the exception's front is exactly the front of the
    designs evaluated until then: a Designer told the same designs reaches the same one."""
    def stop(done, total):
        if done >= 100:
            raise KeyboardInterrupt

    # Runs of 4 s (the preset's are shorter) keep the search well past the first polls.
    with pytest.raises(KeyboardInterrupt) as e:
        thud.design(**PAPER, evaluations=400, seed=4, duration=4, progress=stop)
    front = e.value.front
    assert front.partial and 100 <= front.evaluations < 400, front
    designer = thud.Designer(**PAPER, evaluations=400, seed=4, duration=4)
    while designer.result().evaluations < front.evaluations:
        xs = designer.ask(front.evaluations - designer.result().evaluations)
        designer.tell(xs, [thud.simulate(**designer.base, **x, samples=2) for x in xs])
    same = designer.result()
    assert same.evaluations == front.evaluations
    assert same.designs == front.designs and same.hypervolume == front.hypervolume
    # Any other exception of the callback stops it the same way and carries the front too.

    def fail(done, total):
        if done >= 100:
            raise RuntimeError("enough")

    with pytest.raises(RuntimeError) as e2:
        thud.design(**PAPER, evaluations=400, seed=4, duration=4, progress=fail)
    assert e2.value.front.partial and e2.value.front.evaluations < 400


def stub_keywords(name, cls=None):
    tree = ast.parse(STUB.read_text(encoding="utf-8"))
    nodes = tree.body
    if cls is not None:
        nodes = next(n for n in nodes if isinstance(n, ast.ClassDef) and n.name == cls).body
    fn = next(n for n in nodes if isinstance(n, ast.FunctionDef) and n.name == name)
    return {a.arg: ast.literal_eval(d) for a, d in zip(fn.args.kwonlyargs, fn.args.kw_defaults)}


def test_the_stub_s_keywords_are_the_runtime_s_and_the_engine_s():
    import inspect

    runtime = {p.name: p.default for p in inspect.signature(thud.design).parameters.values()}
    assert stub_keywords("design") == runtime
    # A Designer's caller evaluates the designs: it has no progress of its own.
    assert stub_keywords("__init__", "Designer") == {k: v for k, v in runtime.items() if k != "progress"}
    with pytest.raises(thud.ParameterError) as e:
        thud.design(**PAPER, nonesuch=1)
    engine = set(str(e.value).split("(one of: ")[1].rstrip(")").split(", "))
    search = {"preset", "design", "vary", "choose", "minimize", "maximize", "require", "over", "evaluations",
              "seed", "reference", "no_limit", "progress"}
    assert set(runtime) == engine | search


@pytest.mark.parametrize("cls", ["Front", "Designer"])
def test_every_public_attribute_is_in_the_stub(cls):
    tree = ast.parse(STUB.read_text(encoding="utf-8"))
    node = next(n for n in tree.body if isinstance(n, ast.ClassDef) and n.name == cls)
    stubbed = {n.target.id for n in node.body if isinstance(n, ast.AnnAssign)}
    stubbed |= {n.name for n in node.body if isinstance(n, ast.FunctionDef) and not n.name.startswith("_")}
    obj = thud.design(**PAPER, evaluations=20) if cls == "Front" else thud.Designer(**PAPER, evaluations=20)
    assert stubbed == {n for n in dir(obj) if not n.startswith("_")}
