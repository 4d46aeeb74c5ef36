"""numpy in and out: load's arrays, their CSV round trip, data sets built
from arrays (lists, other dtypes), eval's shapes and values against
hand-derived ones, the catalogue and the export."""

import math

import numpy as np
import pytest

import brdf
from conftest import cli_json, data_file


def test_load_gives_unit_directions_and_values():
    d = brdf.load(data_file("curet/abrdf.dat#25"))
    n = len(d["weights"])
    assert n == 205  # CUReT: 205 measurement pairs per material
    assert d["wi"].shape == d["wo"].shape == (n, 3)
    assert d["values"].shape == (n, 1) and d["channel_names"] == ["grey"]
    assert d["wi"].dtype == d["values"].dtype == np.float64
    np.testing.assert_allclose(np.linalg.norm(d["wi"], axis=1), 1.0, atol=1e-12)
    np.testing.assert_allclose(np.linalg.norm(d["wo"], axis=1), 1.0, atol=1e-12)
    assert d["name"].startswith("curet#25")


def test_rgb_file_loads_three_channels():
    d = brdf.load(data_file("rgl/paper_white_rgb.bsdf"))
    assert d["values"].shape[1] == 3 and len(d["channel_names"]) == 3


def test_csv_round_trip_is_exact(tmp_path):
    d = brdf.load(data_file("rgl/paper_white_rgb.bsdf"))
    out = tmp_path / "samples.csv"
    brdf.save_samples(d, out)
    back = brdf.load(out)
    assert back["channel_names"] == d["channel_names"]
    np.testing.assert_array_equal(back["values"], d["values"])
    np.testing.assert_array_equal(back["weights"], d["weights"])
    # directions pass through spherical angles in the file
    np.testing.assert_allclose(back["wi"], d["wi"], atol=1e-15)
    np.testing.assert_allclose(back["wo"], d["wo"], atol=1e-15)


def test_arrays_of_any_dtype_and_lists_make_the_same_data_set(tmp_path):
    wi = [[0.0, 0.0, 1.0], [0.6, 0.0, 0.8], [0.0, 0.8, 0.6]]
    wo = [[0.0, 0.0, 1.0], [-0.6, 0.0, 0.8], [0.0, -0.6, 0.8]]
    values = [0.5, 0.25, 0.125]
    as_lists = {"wi": wi, "wo": wo, "values": values}
    as_arrays = {"wi": np.array(wi), "wo": np.array(wo, order="F"),
                 "values": np.array(values, dtype=np.float32)[:, None],
                 "weights": np.ones(3, dtype=np.int64), "channel_names": ["grey"]}
    brdf.save_samples(as_lists, tmp_path / "a.csv")
    brdf.save_samples(as_arrays, tmp_path / "b.csv")
    a, b = brdf.load(tmp_path / "a.csv"), brdf.load(tmp_path / "b.csv")
    np.testing.assert_array_equal(a["values"][:, 0], values)
    np.testing.assert_array_equal(a["weights"], [1.0, 1.0, 1.0])  # default weight
    for k in ("wi", "wo", "values", "weights"):
        np.testing.assert_array_equal(a[k], b[k])
    # float32 directions are not unit vectors to 1e-9: refused, not renormalised
    with pytest.raises(brdf.BrdfError, match="row 1: .* directions must be unit vectors"):
        brdf.save_samples({**as_lists, "wi": np.array(wi, dtype=np.float32)}, tmp_path / "c.csv")


def test_lambert_fit_of_arrays_recovers_kd():
    """f = kd/pi exactly: the fit returns kd (hand-derived)."""
    rng = np.random.default_rng(1)
    theta = rng.uniform(0, 1.2, (50, 2))
    phi = rng.uniform(-math.pi, math.pi, (50, 2))
    dirs = [np.stack([np.sin(theta[:, k]) * np.cos(phi[:, k]),
                      np.sin(theta[:, k]) * np.sin(phi[:, k]), np.cos(theta[:, k])], 1)
            for k in range(2)]
    d = {"wi": dirs[0], "wo": dirs[1], "values": np.full(50, 0.3 / math.pi)}
    r = brdf.fit(d, "lambert").report
    assert r["samples_present"] == 50 and r["fits"][0]["data"] == "numpy"
    kd = r["fits"][0]["parameters"][0]
    assert kd["name"] == "kd" and abs(kd["value"] - 0.3) < 1e-12


def test_eval_shapes_and_hand_values():
    wi = np.array([0.0, 0.0, 1.0])
    wo = np.array([[0.0, 0.0, 1.0], [0.6, 0.0, 0.8], [0.0, 0.0, -1.0]])
    f = brdf.eval("lambert", wi, wo, params={"kd": 0.5})
    assert f.shape == (3, 1)
    np.testing.assert_allclose(f[:, 0], [0.5 / math.pi, 0.5 / math.pi, 0.0], rtol=1e-15)
    one = brdf.eval("lambert", wi, wi, params={"kd": 0.5})
    assert one.shape == (1,)
    # Blinn-Phong at the mirror pair: H = N, f = kd/pi + ks (n+2)/(2 pi) (catalogue form)
    m = {"kd": 0.2, "ks": 0.3, "n": 10.0}
    mirror = brdf.eval("blinn-phong", [0.6, 0.0, 0.8], [-0.6, 0.0, 0.8], params=m)
    specs = {p["name"]: p for p in next(x for x in brdf.models()
                                         if x["name"] == "blinn-phong")["parameters"]}
    assert set(specs) == set(m)
    assert mirror.shape == (1,) and mirror[0] > 0.2 / math.pi


def test_eval_rgb_vectorised_equals_one_by_one():
    d = brdf.load(data_file("rgl/paper_white_rgb.bsdf"))
    wi, wo = d["wi"][:40], d["wo"][:40]
    params = {"kd_r": 0.5, "kd_g": 0.4, "kd_b": 0.3}
    many = brdf.eval("lambert", wi, wo, params=params, channels=3)
    assert many.shape == (40, 3)
    for j in range(40):
        np.testing.assert_array_equal(
            many[j], brdf.eval("lambert", wi[j], wo[j], params=params, channels=3))


def test_models_equal_cli(brdf_cli):
    assert brdf.models() == cli_json(brdf_cli, "models")
    assert brdf.models(lobes=2, channels=3) == \
        cli_json(brdf_cli, "models", "--lobes", "2", "--channels", "3")


def test_export_writes_exact_equivalents_only():
    xml = brdf.export("lambert", "mitsuba", params={"kd": 0.5})
    assert 'type="diffuse"' in xml and "0.5" in xml
    with pytest.raises(brdf.BrdfError, match="no exact equivalent"):
        brdf.export("ggx", "mitsuba")
    with pytest.raises(brdf.BrdfError, match="unknown export target `povray`"):
        brdf.export("lambert", "povray")


def test_materials_lists_every_curet_sample():
    every = brdf.materials(data_file("curet/abrdf.dat"))
    assert len(every) == 61 and all("#" in m for m in every)
    assert brdf.materials(data_file("curet/abrdf.dat#3")) == [data_file("curet/abrdf.dat#3")]
