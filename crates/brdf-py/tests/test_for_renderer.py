"""`brdf.fit(data, for_renderer=...)` is `brdf fit --for`: among the models
the renderer renders exactly, the one of least image error, fitted for
appearance; its export to that renderer is exact (no conversion)."""

import pytest

import brdf
from conftest import cli_json, data_file, without_seconds


def test_fit_for_gltf_equals_cli_and_exports_exactly(brdf_cli, tmp_path):
    path = data_file("rgl/paper_white_rgb.bsdf")
    out = tmp_path / "m.gltf"
    cli = cli_json(brdf_cli, "fit", "--data", path, "--for", "gltf", "--out", str(out),
                   "--quiet")
    py = brdf.fit(path, for_renderer="gltf")
    assert without_seconds(py.report) == without_seconds(cli)
    names = [c["model"] for c in py.report["candidates"]]
    assert set(names) <= {"gltf", "gltf-ext"} and names
    flips = [sum(l["flip"] for l in c["image"]["lights"]) for c in py.report["candidates"]]
    assert py.report["choice"]["model"] == names[flips.index(min(flips))]
    assert py.model.name == py.report["choice"]["model"]
    # The chosen model exports to glTF without a conversion (an inexact
    # one is refused unless convert=True), and the command wrote it.
    assert py.model.export(to="gltf")
    assert out.read_text().lstrip().startswith("{")


def test_fit_needs_a_model_or_a_renderer():
    path = data_file("rgl/paper_white_rgb.bsdf")
    with pytest.raises(brdf.BrdfError, match="model=NAME or for_renderer"):
        brdf.fit(path)
