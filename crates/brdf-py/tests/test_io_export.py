"""What the library says rather than does silently, from Python: a CSV
file without weights (a UserWarning), a missing file (the nearest names),
a grey model exported as a coloured material (a UserWarning naming
channels="rgb"); and the glTF export's preview sphere, decoded here from
the file's own buffer."""

import base64
import json
import math
import struct
import warnings

import brdf
import numpy as np
import pytest

from conftest import REPO, data_file

# A saved RGB `gltf` model (paper_white's conversion, committed).
SAVED = REPO / "crates" / "brdf-export" / "tests" / "reference" / "paper_white" / "principled.gltf.json"


def test_csv_without_weights_loads_with_unit_weights_and_warns(tmp_path):
    path = tmp_path / "data.csv"
    path.write_text("theta_i,phi_i,theta_o,phi_o,grey\n0.1,0,0.2,3,0.5\n0.7,1.5,0.3,-2,0.25\n")
    with pytest.warns(UserWarning, match="data.csv: no weight column; every sample weighted 1"):
        d = brdf.load(path)
    assert d["weights"].tolist() == [1.0, 1.0]
    assert d["values"][:, 0].tolist() == [0.5, 0.25]
    assert math.isclose(d["wi"][0, 2], math.cos(0.1), rel_tol=0, abs_tol=1e-15)


def test_csv_with_weights_is_read_as_written_without_a_warning(tmp_path):
    path = tmp_path / "w.csv"
    path.write_text("theta_i,phi_i,theta_o,phi_o,grey,weight\n0.1,0,0.2,3,0.5,0.25\n")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        d = brdf.load(path)
    assert d["weights"].tolist() == [0.25]


def test_a_missing_file_names_the_nearest(tmp_path):
    (tmp_path / "paper_white_rgb.bsdf").write_bytes(b"")
    want = str(tmp_path / "paper_white_rgb.bsdf")
    with pytest.raises(brdf.BrdfError, match="did you mean") as e:
        brdf.load(tmp_path / "paper_white.bsdf")
    assert want in str(e.value)
    # Model.tabulate resolves its grid as data paths are resolved.
    model = brdf.Model.load(SAVED)
    with pytest.raises(brdf.BrdfError, match="did you mean") as e:
        model.tabulate(tmp_path / "paper_white.bsdf")
    assert want in str(e.value)


def test_tabulate_finds_a_relative_grid_under_brdf_data(tmp_path, monkeypatch):
    grid = data_file("rgl/paper_white_rgb.bsdf")
    model = brdf.Model.load(SAVED)
    want = model.tabulate(grid)
    monkeypatch.chdir(tmp_path)
    assert model.tabulate("rgl/paper_white_rgb.bsdf") == want


def test_a_grey_model_exported_as_a_material_warns_that_its_colour_was_never_fitted():
    with pytest.warns(UserWarning, match=r'one channel: its colour was never fitted.*channels="rgb"'):
        brdf.export("lambert", "gltf", params={"kd": 0.5})
    with pytest.warns(UserWarning, match="never fitted"):
        brdf.export("principled", "mitsuba")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        brdf.export("lambert", "gltf", channels=3)


def _accessor(asset, raw, k, fmt, width):
    acc = asset["accessors"][k]
    view = asset["bufferViews"][acc["bufferView"]]
    start = view.get("byteOffset", 0)
    data = raw[start:start + view["byteLength"]]
    n = acc["count"] * width
    return np.array(struct.unpack("<" + fmt * n, data[: n * struct.calcsize(fmt)])).reshape(-1, width)


def test_gltf_carries_a_preview_sphere_unless_mesh_is_false():
    asset = json.loads(brdf.export("lambert", "gltf", params={"kd_r": 0.5, "kd_g": 0.4, "kd_b": 0.3}, channels=3))
    (mesh,) = asset["meshes"]
    (prim,) = mesh["primitives"]
    assert prim["material"] == 0 and len(asset["materials"]) == 1
    assert asset["scenes"][asset["scene"]]["nodes"] == [0] and asset["nodes"][0]["mesh"] == 0
    uri = asset["buffers"][0]["uri"]
    raw = base64.b64decode(uri.split(",", 1)[1])
    assert len(raw) == asset["buffers"][0]["byteLength"]
    pos = _accessor(asset, raw, prim["attributes"]["POSITION"], "f", 3)
    nor = _accessor(asset, raw, prim["attributes"]["NORMAL"], "f", 3)
    idx = _accessor(asset, raw, prim["indices"], "H", 1).ravel()
    assert len(pos) == len(nor) > 0
    assert np.allclose(np.linalg.norm(nor, axis=1), 1.0, atol=1e-6)
    assert idx.max() < len(pos) and len(idx) % 3 == 0
    library = json.loads(brdf.export("lambert", "gltf", params={"kd_r": 0.5, "kd_g": 0.4, "kd_b": 0.3}, channels=3, mesh=False))
    assert "meshes" not in library and "buffers" not in library
    assert library["materials"] == asset["materials"]
    m = brdf.Model.load(SAVED)
    assert "meshes" in json.loads(m.export(to="gltf"))
    assert "meshes" not in json.loads(m.export(to="gltf", mesh=False))
