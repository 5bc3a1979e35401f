"""Line contacts (plane strain) in Python: 1-D fields of shape (nx,), a summary
without y keys, a Dataset on the one dimension x, and the Hertz line contact's
half-width and peak pressure against the closed form."""

import math
import pathlib

import numpy as np
import pytest

import thirdbody

ROOT = pathlib.Path(__file__).resolve().parents[3]
HERTZ_LINE = ROOT / "examples" / "hertz_line.toml"
Y_KEYS = ("contact_y_min", "contact_y_max", "max_pressure_y", "ny", "window_y_min",
          "window_y_max")


@pytest.fixture(scope="module")
def line():
    return thirdbody.solve(thirdbody.Case.from_file(HERTZ_LINE))


def test_hertz_line_contact_matches_the_closed_form(line):
    # Johnson, Contact Mechanics, section 4.3: a = (4 Q R / (pi E*))^(1/2),
    # p0 = 2 Q / (pi a), E* = E / (1 - nu^2); here Q = 1e-3 per unit length, R = 1,
    # E = 1, nu = 0.3, 1024 cells.
    q, r, e, nu = 1e-3, 1.0, 1.0, 0.3
    e_star = e / (1 - nu**2)
    a = math.sqrt(4 * q * r / (math.pi * e_star))
    p0 = 2 * q / (math.pi * a)
    s = line.summary
    half_width = 0.5 * (s["contact_x_max"] - s["contact_x_min"])
    assert half_width == pytest.approx(a, rel=2e-3)
    assert s["contact_area"] == pytest.approx(2 * a, rel=2e-3)
    assert s["max_pressure"] == pytest.approx(p0, rel=2e-3)
    # The load per unit length is the pressure summed over strips of width h.
    assert line.pressure.sum() * s["cell_size"] == pytest.approx(q, rel=1e-8)


def test_a_line_contact_has_1d_fields_and_no_y(line):
    nx = line.summary["nx"]
    assert nx == 1024
    for field in (line.pressure, line.gap, line.body_displacement):
        assert field.shape == (nx,)
    assert line.x.shape == (nx,)
    assert line.y is None
    assert line.is_line
    s = line.summary
    assert s["contact"] == "line" and s["reference_distance"] == 1.0
    for key in Y_KEYS:
        assert key not in s, key
    with pytest.raises(ValueError, match="y = 0.5"):
        line.stresses("xz", y=0.5)


def test_a_point_contact_keeps_its_2d_fields():
    case = thirdbody.Case.from_file(ROOT / "examples" / "hertz.toml")
    point = thirdbody.solve(case)
    assert point.pressure.shape == (128, 128) == case.cells
    assert not point.is_line and point.y is not None
    assert "contact" not in point.summary
    for key in Y_KEYS:
        assert key in point.summary, key


def test_to_xarray_of_a_line_contact_has_one_dimension(line):
    xarray = pytest.importorskip("xarray")
    data = line.to_xarray()
    assert isinstance(data, xarray.Dataset)
    assert data["pressure"].dims == ("x",)
    assert "y" not in data.coords
    np.testing.assert_array_equal(data["pressure"].values, line.pressure)
    assert data.attrs["contact"] == "line"
    assert "contact_y_min" not in data.attrs


def test_a_profile_given_as_an_array_equals_the_same_npy_file_and_pickles(tmp_path):
    # The cylinder x^2 / 2 sampled every 1e-6 over +-0.06: as a 1-D numpy array and as
    # the same array saved to NPY, the two cases are one case (hash and results).
    import pickle

    x = (np.arange(120_001) - 60_000) * 1e-6
    heights = x**2 / 2.0 + 0.25
    np.save(tmp_path / "profile.npy", heights)
    common = {"substrate": {"young": 1.0, "poisson": 0.3},
              "loading": {"normal_load": 1e-3}, "grid": {"cells": 512, "half_width": 0.05}}
    from_array = thirdbody.Case(
        slider={"shape": "profile", "heights": heights, "cell_size": 1e-6}, **common)
    text = (f'[slider]\nshape = "profile"\nfile = "profile.npy"\ncell_size = 1e-6\n'
            '[substrate]\nyoung = 1.0\npoisson = 0.3\n[loading]\nnormal_load = 1e-3\n'
            '[grid]\ncells = 512\nhalf_width = 0.05\n')
    from_file = thirdbody.Case.from_toml(text, base_dir=tmp_path)
    assert from_array.case_hash == from_file.case_hash
    events = []
    a, b = thirdbody.solve(from_array, progress=events.append), thirdbody.solve(from_file)
    np.testing.assert_array_equal(a.pressure, b.pressure)
    assert a.is_line and a.pressure.shape == (512,)
    # The case's cells and the progress events' cells have the fields' shape.
    assert from_array.cells == (512,)
    windows = [e for e in events if e["event"] == "window"]
    assert windows and all(e["cells"] == (512,) and len(e["half_width"]) == 1 for e in windows)
    again = pickle.loads(pickle.dumps(from_array))
    assert again.case_hash == from_array.case_hash
    # A 2-D map given as a profile names the file and the other shape.
    with pytest.raises(ValueError, match="height_map"):
        thirdbody.Case(slider={"shape": "profile", "heights": np.zeros((3, 4)),
                               "cell_size": 1.0}, **common)
