"""Python fits equal the `brdf` command's fits on CUReT materials, number
for number (only the wall-clock time differs), from a path and from numpy
arrays; saved models evaluate as `brdf eval --load`; fits release the GIL."""

import math
import threading
import time

import numpy as np
import pytest

import brdf
from conftest import cli_json, data_file, without_seconds

MATERIALS = ["curet/abrdf.dat#1", "curet/abrdf.dat#25", "curet/abrdf.dat#44"]
MODELS = ["lambert", "blinn-phong", "ashikhmin-shirley", "cook-torrance"]


@pytest.mark.parametrize("material", MATERIALS)
@pytest.mark.parametrize("model", MODELS)
def test_fit_equals_cli(brdf_cli, material, model):
    path = data_file(material)
    cli = cli_json(brdf_cli, "fit", "--data", path, "--model", model)
    py = brdf.fit(path, model).report
    assert without_seconds(py) == without_seconds(cli)
    assert py["fits"][0]["seconds"] > 0


@pytest.mark.parametrize(
    "model, options, flags",
    [
        ("ward", dict(channels="per-channel", metric="log", limit_deg=60.0, starts=5),
         ["--channels", "per-channel", "--metric", "log", "--limit", "60", "--starts", "5"]),
        ("lafortune", dict(channels="grey", solver="lm", lobes=2),
         ["--channels", "grey", "--solver", "lm", "--lobes", "2"]),
        # The degree-3 fit of quarry tile cycles: the cap decides where it stops.
        ("polynomial", dict(degree=3, irls_max_iterations=50),
         ["--degree", "3", "--irls-max-iterations", "50"]),
    ],
)
def test_fit_options_equal_cli(brdf_cli, model, options, flags):
    path = data_file("curet/abrdf.dat#25")
    cli = cli_json(brdf_cli, "fit", "--data", path, "--model", model, *flags)
    py = brdf.fit(path, model, **options).report
    assert without_seconds(py) == without_seconds(cli)


def test_fit_of_rgb_file_equals_cli(brdf_cli):
    path = data_file("rgl/paper_white_rgb.bsdf")
    cli = cli_json(brdf_cli, "fit", "--data", path, "--model", "ward", "--starts", "4")
    py = brdf.fit(path, "ward", starts=4).report
    assert len(py["fits"][0]["ngan_l2_per_channel"]) == 3
    assert without_seconds(py) == without_seconds(cli)


def test_image_objective_fit_equals_cli(brdf_cli):
    # `metric="image"` starts from the Ngan fit and refines the render,
    # as `brdf fit --metric image` does.
    path = data_file("rgl/paper_white_rgb.bsdf")
    cli = cli_json(brdf_cli, "fit", "--data", path, "--model", "ggx", "--metric", "image")
    py = brdf.fit(path, "ggx", metric="image").report
    assert py["fits"][0]["objective"] == "image"
    assert without_seconds(py) == without_seconds(cli)


@pytest.mark.parametrize("material", MATERIALS)
def test_fit_from_arrays_equals_fit_from_path(material):
    path = data_file(material)
    from_arrays = brdf.fit(brdf.load(path), "blinn-phong").report
    from_path = brdf.fit(path, "blinn-phong").report
    assert without_seconds(from_arrays) == without_seconds(from_path)


def test_saved_model_evaluates_as_cli(brdf_cli, tmp_path):
    path = data_file("curet/abrdf.dat#25")
    saved = tmp_path / "fit.json"
    report = brdf.fit(path, "ashikhmin-shirley", save=saved).report
    fitted = {p["name"]: p["value"] for p in report["fits"][0]["parameters"]}
    params = [(0.3, 0.0, 0.5, math.pi), (1.0, 0.5, 0.2, 2.0), (0.1, 1.0, 1.2, -2.5)]
    for ti, pi, to, po in params:
        cli = cli_json(brdf_cli, "eval", "--load", str(saved),
                       "--wi", f"{ti},{pi}", "--wo", f"{to},{po}")
        assert dict(cli["parameters"]) == fitted
        wi = np.array([math.sin(ti) * math.cos(pi), math.sin(ti) * math.sin(pi), math.cos(ti)])
        wo = np.array([math.sin(to) * math.cos(po), math.sin(to) * math.sin(po), math.cos(to)])
        np.testing.assert_allclose(brdf.eval(saved, wi, wo), cli["channels"], rtol=1e-12)
        # the saved file reads back the fitted numbers exactly
        assert brdf.eval(saved, wi, wo).tolist() == \
            brdf.eval("ashikhmin-shirley", wi, wo, params=fitted).tolist()
        # the saved file's content as a dict names the same model
        import json
        as_dict = json.loads(saved.read_text())
        assert brdf.eval(as_dict, wi, wo).tolist() == brdf.eval(str(saved), wi, wo).tolist()


def test_fit_releases_the_gil():
    """While a fit runs in one thread, Python code runs in another."""
    path = data_file("curet/abrdf.dat#25")
    span = {}

    def work():
        span["start"] = time.perf_counter()
        brdf.fit(path, "cook-torrance", lobes=2, starts=200)
        span["end"] = time.perf_counter()

    ticks = []
    t = threading.Thread(target=work)
    t.start()
    while t.is_alive():
        ticks.append(time.perf_counter())
        time.sleep(0.001)
    t.join()
    inside = [x for x in ticks if span["start"] < x < span["end"]]
    # A fit holding the GIL would leave no tick inside it (the main thread
    # cannot run Python while it is held); released, one every ~1 ms.
    assert span["end"] - span["start"] > 0.05, "the fit was too short to tell"
    assert len(inside) >= 10, f"{len(inside)} ticks during a {span['end'] - span['start']:.3f} s fit"


def test_fit_object_model_evaluates_saves_and_loads(tmp_path):
    path = data_file("curet/abrdf.dat#25")
    fit = brdf.fit(path, "blinn-phong")
    assert isinstance(fit, brdf.Fit) and isinstance(fit.model, brdf.Model)
    assert fit.image_error is None
    fitted = {p["name"]: p["value"] for p in fit.report["fits"][0]["parameters"]}
    assert fit.model.params == fitted
    assert repr(fit).startswith('Fit(model="blinn-phong"') and "ngan_l2" in repr(fit)
    assert "blinn-phong" in repr(fit.model)
    theta = np.linspace(0.0, 1.2, 7)
    wi = np.stack([np.sin(theta), np.zeros_like(theta), np.cos(theta)], axis=1)
    wo = wi[::-1].copy()
    values = fit.model.eval(wi, wo)
    assert values.shape == (7, fit.model.channels)
    assert values.tolist() == brdf.eval("blinn-phong", wi, wo, params=fitted).tolist()
    saved = tmp_path / "m.json"
    fit.model.save(saved)
    assert brdf.Model.load(saved).eval(wi, wo).tolist() == values.tolist()
    assert brdf.Model.load(str(saved)).params == fitted


def test_model_renders_the_judge_sphere():
    fit = brdf.fit(data_file("curet/abrdf.dat#25"), "lambert")
    kd = fit.model.params["kd"]
    image = fit.model.render(light="directional", size=33)
    assert image.shape == (33, 33, 3) and image.dtype == np.float64
    # The centre pixel sees the sphere's pole (normal +z) lit by the
    # study's light (0.5, 0.5, 0.707) of irradiance 1: kd / pi * cos.
    light = np.array([0.5, 0.5, 0.707])
    expected = kd / math.pi * light[2] / np.linalg.norm(light)
    assert image[16, 16].tolist() == pytest.approx([expected] * 3, rel=1e-9)
    assert image[0, 0].tolist() == [0.0, 0.0, 0.0]  # off the sphere, no background
    studio = fit.model.render(size=32)
    assert studio.shape == (32, 32, 3) and np.all(np.isfinite(studio)) and studio.max() > 0
    with pytest.raises(brdf.BrdfError, match="moon"):
        fit.model.render(light="moon")
    with pytest.raises(brdf.BrdfError, match="size=8"):
        fit.model.render(size=8)


def test_per_channel_fit_has_a_model_per_channel():
    path = data_file("rgl/paper_white_rgb.bsdf")
    fit = brdf.fit(path, "lambert", channels="per-channel", starts=2)
    assert len(fit.models) == 3 and len(fit.report["fits"]) == 3


def test_image_error_of_a_fit_to_dense_data():
    path = data_file("rgl/paper_white_rgb.bsdf")
    fit = brdf.fit(path, "lambert", starts=2)
    err = fit.image_error
    assert isinstance(err, dict) and err, err
    assert [l["light"] for l in err["lights"]] == ["sky", "studio"]
    # A white paper keeps close to one plane of white and one colour.
    plane = err["colour_plane"]
    assert plane["light"] == "studio" and 0.0 < plane["outside"] < 0.005, plane


def test_model_load_refuses_a_data_file():
    path = data_file("rgl/paper_white_rgb.bsdf")
    with pytest.raises(brdf.BrdfError, match="is a data file"):
        brdf.Model.load(path)


def test_every_function_has_a_numpy_style_docstring():
    functions = [brdf.load, brdf.save_samples, brdf.fit, brdf.eval, brdf.export, brdf.models,
                 brdf.materials, brdf.canonical_name, brdf.data_name,
                 brdf.Model.load, brdf.Model.eval, brdf.Model.export, brdf.Model.save,
                 brdf.Model.render]
    for f in functions:
        doc = f.__doc__ or ""
        assert "Parameters" in doc or "Returns" in doc, f


def test_polish_equals_cli(brdf_cli):
    path = data_file("rgl/paper_white_rgb.bsdf")
    cli = cli_json(brdf_cli, "fit", "--data", path, "--model", "ggx", "--polish")
    py = brdf.fit(path, "ggx", polish=True).report
    assert without_seconds(py) == without_seconds(cli)
    assert py["candidates"][0][-1]["objective"] == "flip"


def test_polish_needs_a_fit_for_appearance():
    with pytest.raises(brdf.BrdfError, match="polish=True refines a fit for appearance"):
        brdf.fit(data_file("curet/abrdf.dat#25"), "ggx", channels="grey", polish=True)
