"""An image test as a pytest user writes one: render, compare with a reference noise-aware, and
assert the verdict; a changed renderer fails it."""

import numpy as np

import rtiow


def test_the_cover_matches_its_reference(tmp_path):
    scene = rtiow.builtin_scene("cover")
    reference = rtiow.render(scene, width=64, spp=64, seed=1, stats_channels=True)
    reference.write(str(tmp_path / "reference.exr"))
    test = rtiow.render(scene, width=64, spp=64, seed=2, stats_channels=True)
    verdict = rtiow.diff(test, str(tmp_path / "reference.exr"))
    assert verdict["mode"] == "noise"
    assert verdict["passed"], verdict["description"]


def test_a_changed_renderer_fails_the_image_test(tmp_path):
    scene = rtiow.builtin_scene("cover")
    reference = rtiow.render(scene, width=64, spp=64, seed=1, stats_channels=True)
    shallow = rtiow.render(scene, width=64, spp=64, seed=2, stats_channels=True, depth=2)
    verdict = rtiow.diff(shallow, reference)
    assert not verdict["passed"], verdict["description"]


def test_a_written_render_reads_back_as_it_was(tmp_path):
    render = rtiow.render(rtiow.builtin_scene("cover"), width=40, spp=4, passes=["depth"])
    render.write(str(tmp_path / "r.exr"))
    assert np.array_equal(rtiow.read_image(str(tmp_path / "r.exr")), render.image)
    assert list(render.passes) == ["Z"]
    assert render.summary["samples"] == "4 spp"
