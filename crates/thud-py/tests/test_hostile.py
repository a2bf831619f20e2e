"""Hostile arguments to the design search and the basins: each a ParameterError naming the
keyword, never a bare OverflowError, TypeError or ValueError from inside."""

import pytest

import thud

SEARCH = dict(vary="mass=20g:120g", minimize="spl_max_db", evaluations=8, seed=1)


def test_asking_for_more_points_than_a_search_holds_gives_what_there_is():
    d = thud.Designer(**SEARCH)
    points = d.ask(10**20)
    assert 1 <= len(points) <= 8 and d.outstanding == len(points)


@pytest.mark.parametrize("value", ["loud", [1.0], {}])
def test_a_told_result_that_is_not_a_number_names_results(value):
    d = thud.Designer(**SEARCH)
    xs = d.ask(1)
    with pytest.raises(thud.ParameterError) as e:
        d.tell(xs, [{"spl_max_db": value}])
    assert e.value.param == "results" and "spl_max_db" in str(e.value)
    assert d.outstanding == 1


@pytest.mark.parametrize("w0", [1, None, (1, 2, 3), "-1:1"])
def test_basins_w0_must_be_two_speeds(w0):
    with pytest.raises(thud.ParameterError) as e:
        thud.basins(grid=2, w0=w0, freq=5, force_amplitude=1)
    assert e.value.param == "w0" and "\n" not in str(e.value)
