"""A render farm from Python: shares of a render's samples written as part files and merged
give the image one render of all the samples gives, bit for bit, and the command line's merge
of the same parts."""

import numpy as np
import pytest

import rtiow


def test_parts_merge_into_the_whole_render(run_rtiow, tmp_path):
    scene = rtiow.builtin_scene("cover")
    whole = rtiow.render(scene, width=48, spp=6, passes="depth")
    parts = []
    for i, share in enumerate(["0/3", "1/3", "2/3"]):
        part = rtiow.render(scene, width=48, spp=6, passes="depth", part=share)
        assert (part.spp == 2).all()
        parts.append(str(tmp_path / f"p{i}.exr"))
        part.write(parts[-1])
    rtiow.merge(parts, str(tmp_path / "merged.exr"))
    assert np.array_equal(rtiow.read_image(str(tmp_path / "merged.exr")), whole.image)
    code, err = run_rtiow("merge", *parts, "-o", tmp_path / "cli.exr")
    assert code == 0, err
    assert np.array_equal(rtiow.read_image(str(tmp_path / "cli.exr")), whole.image)


def test_a_sample_range_is_a_share_too(tmp_path):
    scene = rtiow.builtin_scene("cover")
    first = rtiow.render(scene, width=32, spp=4, sample_range="0:1")
    rest = rtiow.render(scene, width=32, spp=4, sample_range="1:4")
    first.write(str(tmp_path / "a.exr"))
    rest.write(str(tmp_path / "b.exr"))
    rtiow.merge([str(tmp_path / "a.exr"), str(tmp_path / "b.exr")], str(tmp_path / "m.exr"))
    whole = rtiow.render(scene, width=32, spp=4)
    assert np.array_equal(rtiow.read_image(str(tmp_path / "m.exr")), whole.image)


def test_parts_that_do_not_belong_together_are_refused(tmp_path):
    scene = rtiow.builtin_scene("cover")
    rtiow.render(scene, width=32, spp=4, part="0/2").write(str(tmp_path / "a.exr"))
    rtiow.render(scene, width=32, spp=4, seed=2, part="1/2").write(str(tmp_path / "b.exr"))
    with pytest.raises(ValueError, match="seed"):
        rtiow.merge([str(tmp_path / "a.exr"), str(tmp_path / "b.exr")], str(tmp_path / "m.exr"))
    with pytest.raises(ValueError, match="part"):
        rtiow.render(scene, width=32, spp=4, part="2/2")
