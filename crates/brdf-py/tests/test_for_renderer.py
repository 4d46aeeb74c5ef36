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
                   "--limit", "75", "--quiet")
    py = brdf.fit(path, for_renderer="gltf", limit_deg=75.0)
    assert without_seconds(py.report) == without_seconds(cli)
    assert {c["limit_deg"] for c in py.report["candidates"]} == {75.0}
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


@pytest.mark.parametrize("option", [dict(metric="ngan"), dict(channels="grey"),
                                    dict(starts=3), dict(solver="lm"), dict(lobes=2)])
def test_fit_for_refuses_what_it_decides_itself(option):
    path = data_file("rgl/paper_white_rgb.bsdf")
    name = next(iter(option))
    with pytest.raises(brdf.BrdfError, match=f"{name}= has no use with for_renderer="):
        brdf.fit(path, for_renderer="mitsuba", **option)
