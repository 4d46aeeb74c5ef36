"""Bad input raises brdf.BrdfError (a ValueError) carrying the Rust message,
which names the file, line, parameter or argument at fault."""

import json

import numpy as np
import pytest

import brdf


def test_missing_file_is_named(tmp_path):
    missing = tmp_path / "nothing.bsdf"
    with pytest.raises(brdf.BrdfError, match="nothing.bsdf"):
        brdf.load(missing)
    with pytest.raises(brdf.BrdfError, match="nothing.bsdf"):
        brdf.fit(missing, "lambert")


def test_bad_csv_names_file_and_line(tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text("theta_i,phi_i,theta_o,phi_o,grey,weight\n0.1,0,0.2,0,0.5,1\n0.1,0,x,0,0.5,1\n")
    with pytest.raises(brdf.BrdfError, match=r"bad\.csv:3") as e:
        brdf.load(bad)
    assert isinstance(e.value, ValueError)
    with pytest.raises(brdf.BrdfError, match=r"bad\.csv:3"):
        brdf.fit(bad, "lambert")


def test_unknown_format_is_named(tmp_path):
    odd = tmp_path / "data.xyz"
    odd.write_text("1 2 3\n")
    with pytest.raises(brdf.BrdfError, match="data.xyz"):
        brdf.load(odd)


def test_broken_saved_model_is_named(tmp_path):
    saved = tmp_path / "model.json"
    saved.write_text('{"schema": "brdf-fit/model"')
    with pytest.raises(brdf.BrdfError, match="model.json"):
        brdf.eval(saved, [0, 0, 1], [0, 0, 1])
    with pytest.raises(brdf.BrdfError, match="model.json"):
        brdf.export(str(saved), "mitsuba")


def test_unknown_model_suggests_names():
    with pytest.raises(brdf.BrdfError, match="blinn-phong"):
        brdf.eval("blinn-phon", [0, 0, 1], [0, 0, 1])
    with pytest.raises(brdf.BrdfError, match="blinn-phong"):
        brdf.canonical_name("blin phong")


def test_bad_options_are_named(tmp_path):
    d = {"wi": [[0, 0, 1]], "wo": [[0, 0, 1]], "values": [0.1]}
    with pytest.raises(brdf.BrdfError, match='channels="bogus"'):
        brdf.fit(d, "lambert", channels="bogus")
    with pytest.raises(brdf.BrdfError, match="angle limit 95"):
        brdf.fit(d, "lambert", limit_deg=95.0)
    with pytest.raises(brdf.BrdfError, match="starts = 0"):
        brdf.fit(d, "lambert", starts=0)
    with pytest.raises(brdf.BrdfError, match="parameter"):
        brdf.eval("lambert", [0, 0, 1], [0, 0, 1], params={"kd": -1.0})
    with pytest.raises(brdf.BrdfError, match="nope"):
        brdf.eval("lambert", [0, 0, 1], [0, 0, 1], params={"nope": 1.0})


def test_bad_arrays_are_named():
    with pytest.raises(brdf.BrdfError, match=r"wo row 1: .* has length 2"):
        brdf.eval("lambert", [0, 0, 1], [[0, 0, 1], [0, 0, 2]])
    with pytest.raises(brdf.BrdfError, match=r"wi: shape \[2\]"):
        brdf.eval("lambert", [0, 1], [0, 0, 1])
    with pytest.raises(brdf.BrdfError, match="wi has 2 rows, wo 3"):
        brdf.eval("lambert", np.tile([0, 0, 1.0], (2, 1)), np.tile([0, 0, 1.0], (3, 1)))
    base = {"wi": [[0, 0, 1]], "wo": [[0, 0, 1]], "values": [0.1]}
    with pytest.raises(brdf.BrdfError, match="no `values` array"):
        brdf.fit({k: v for k, v in base.items() if k != "values"}, "lambert")
    with pytest.raises(brdf.BrdfError, match="`weights` has 2 entries for 1"):
        brdf.fit({**base, "weights": [1.0, 2.0]}, "lambert")
    with pytest.raises(brdf.BrdfError, match="weight"):
        brdf.fit({**base, "weights": [-1.0]}, "lambert")
    with pytest.raises(brdf.BrdfError, match="data `wi` row 0"):
        brdf.fit({**base, "wi": [[np.nan, 0, 1]]}, "lambert")


def test_params_with_a_saved_model_is_refused(tmp_path):
    saved = tmp_path / "m.json"
    two = {"wi": [[0, 0, 1], [0.6, 0, 0.8]], "wo": [[0, 0, 1], [0, 0.6, 0.8]], "values": [0.1, 0.2]}
    brdf.fit(two, "lambert", save=saved)
    assert json.loads(saved.read_text())["model"] == "lambert"
    with pytest.raises(brdf.BrdfError, match="m.json carries its own"):
        brdf.eval(saved, [0, 0, 1], [0, 0, 1], params={"kd": 0.1})
