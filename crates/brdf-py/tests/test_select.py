"""Python selections equal the `brdf select` command's, number for number
(only the wall-clock times differ): on a measured RGB file, with the
choice's image errors, and on numpy arrays of scattered data, which say why
they have none; selections by image error (the default on files that can be
rendered, `by_image=True`, with or without
`polish=True`) equal `brdf select --by-image`'s; bad arguments raise
BrdfError naming the fix."""

import pytest

import brdf
from conftest import cli_json, data_file, without_seconds


def test_select_of_rgb_file_equals_cli(brdf_cli):
    path = data_file("rgl/paper_white_rgb.bsdf")
    models = "lambert,ward,ggx"
    cli = cli_json(brdf_cli, "select", "--data", path, "--by-l2", "--models", models, "--quiet")
    py = brdf.select(path, by_image=False, models=models.split(","))
    assert without_seconds(py) == without_seconds(cli)
    assert py["choice"]["model"] in models.split(",")
    lights = [l["light"] for l in py["choice_image_error"]["lights"]]
    assert lights == ["sky", "studio"]
    assert py["image_note"] is None


def test_select_of_arrays_equals_cli_and_has_no_image_error(brdf_cli):
    path = data_file("curet/abrdf.dat#25")
    flags = ["--models", "lambert,blinn-phong", "--tolerance", "0.2", "--exhaustive", "--grey"]
    cli = cli_json(brdf_cli, "select", "--data", path, *flags, "--quiet")
    py = brdf.select(brdf.load(path), models=["lambert", "blinn-phong"], tolerance=0.2,
                     exhaustive=True, grey=True)
    assert without_seconds(py) == without_seconds(cli)
    assert py["search"] == "exhaustive"
    assert py["choice_image_error"] is None
    assert "no image error" in py["image_note"]


@pytest.mark.parametrize(
    "options, words",
    [(dict(models=[]), "models=[]"), (dict(models=[], by_image=True), "models=[]"),
     (dict(tolerance=-1.0), "tolerance"),
     (dict(limit_deg=120.0), "limit"), (dict(models=["no-such-model"]), "no-such-model")],
)
def test_bad_arguments_raise_brdf_error(options, words):
    path = data_file("curet/abrdf.dat#25")
    with pytest.raises(brdf.BrdfError, match=words.replace("[", r"\[").replace("]", r"\]")):
        brdf.select(path, **options)


@pytest.mark.parametrize("polish", [False, True])
def test_select_by_image_equals_cli(brdf_cli, polish):
    # GGX alone: the fastest renderer model (a few seconds, polished too).
    path = data_file("rgl/paper_white_rgb.bsdf")
    flags = ["--polish"] if polish else []
    cli = cli_json(brdf_cli, "select", "--data", path, "--by-image", "--models", "ggx",
                   *flags, "--quiet")
    py = brdf.select(path, by_image=True, models=["ggx"], polish=polish)
    assert without_seconds(py) == without_seconds(cli)
    assert py["choice"]["model"] == "ggx"
    assert [l["light"] for l in py["choice"]["image"]["lights"]] == ["sky", "studio"]


def test_select_of_renderable_file_is_by_image_by_default():
    # What the user looks at decides where it can be measured: by default a
    # file that can be rendered is selected by image error, as by_image=True.
    path = data_file("rgl/paper_white_rgb.bsdf")
    default = brdf.select(path, models=["ggx"])
    explicit = brdf.select(path, by_image=True, models=["ggx"])
    assert without_seconds(default) == without_seconds(explicit)
    assert default["choice"]["image"]["lights"][0]["light"] == "sky"


def test_select_by_image_of_arrays_raises_brdf_error():
    arrays = brdf.load(data_file("curet/abrdf.dat#25"))
    with pytest.raises(brdf.BrdfError, match="by_image"):
        brdf.select(arrays, by_image=True, models=["ggx"])


def test_select_by_image_of_scattered_file_raises_brdf_error():
    path = data_file("curet/abrdf.dat#25")
    with pytest.raises(brdf.BrdfError, match="by_image.*scattered"):
        brdf.select(path, by_image=True, models=["ggx"])


def test_polish_without_by_image_raises_brdf_error():
    path = data_file("curet/abrdf.dat#25")
    with pytest.raises(brdf.BrdfError, match="polish=True.*by_image=True"):
        brdf.select(path, polish=True, models=["ggx"])


@pytest.mark.parametrize("option", [dict(tolerance=0.2), dict(grey=True), dict(exhaustive=True),
                                    dict(max_parameters=4)])
def test_a_selection_by_image_refuses_the_options_of_one_by_l2(option):
    path = data_file("rgl/paper_white_rgb.bsdf")
    name = next(iter(option))
    with pytest.raises(brdf.BrdfError, match=f"{name}= applies to a selection by L2"):
        brdf.select(path, **option)
