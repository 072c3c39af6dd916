"""Scenes built in Python: a dict in the scene file's words is the scene that file is (the
command line renders the file to the same pixels), every check a file gets, each error naming
its place; a scene's to_dict() gives it back whole."""

import json

import numpy as np
import pytest

import rtiow


def two_spheres():
    return {
        "version": 1,
        "name": "two spheres",
        "camera": {"lookfrom": [13, 2, 3], "lookat": [0, 0, 0], "vfov": 20},
        "image": {"width": 64, "aspect_ratio": 1.5, "spp": 4, "depth": 10},
        "materials": {
            "ground": {"type": "lambertian", "albedo": np.array([0.5, 0.5, 0.5])},
            "glass": {"type": "dielectric", "ior": 1.5},
            "steel": {"type": "metal", "albedo": [0.7, 0.6, 0.5], "fuzz": 0.1},
        },
        "spheres": [
            {"center": [0, -1000, 0], "radius": 1000, "material": "ground"},
            {"center": [0, 1, 0], "radius": 1, "material": "glass"},
            {"center": [4, 1, 0], "radius": 1, "material": "steel"},
        ],
    }


def test_a_dict_is_the_scene_its_file_is(run_rtiow, tmp_path):
    description = two_spheres()
    scene = rtiow.scene(description)
    assert scene.name == "two spheres" and scene.spheres == 3
    description["materials"]["ground"]["albedo"] = [0.5, 0.5, 0.5]
    (tmp_path / "two.json").write_text(json.dumps(description))
    code, err = run_rtiow("render", "-q", tmp_path / "two.json", "-o", tmp_path / "two.exr")
    assert code == 0, err
    assert np.array_equal(rtiow.render(scene).image, rtiow.read_image(str(tmp_path / "two.exr")))


def test_to_dict_gives_the_scene_back():
    cover = rtiow.builtin_scene("cover")
    again = rtiow.scene(cover.to_dict())
    assert again.spheres == cover.spheres
    assert np.array_equal(rtiow.render(again, width=40, spp=2).image,
                          rtiow.render(cover, width=40, spp=2).image)


@pytest.mark.parametrize("change, message", [
    (lambda d: d["materials"]["glass"].update(type="glas"), "/materials/glass/type"),
    (lambda d: d["spheres"][1].update(radius=float("nan")), "not JSON compliant"),
    (lambda d: d["spheres"][1].update(material="gold"), "/spheres/1/material"),
    (lambda d: d["spheres"][2].update(centre=[0, 0, 0]), "centre"),
    (lambda d: d.pop("image"), 'missing field "image"'),
    (lambda d: d["spheres"][0].update(radius=object()), "object is not a JSON value"),
])
def test_a_bad_scene_is_refused_naming_the_place(change, message):
    description = two_spheres()
    change(description)
    with pytest.raises(ValueError) as refused:
        rtiow.scene(description)
    assert message in str(refused.value)
    assert str(refused.value).startswith("scene dict: ")
