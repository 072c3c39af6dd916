"""rtiow.render_like(image) renders again what an image records, as rtiow render --like does: the
same file byte for byte, each keyword given replacing its part, and a scene that is no longer
the image's refused."""

import json

import numpy as np
import pytest

import rtiow


def test_an_image_renders_again_to_the_same_bytes(run_rtiow, tmp_path):
    first = tmp_path / "first.exr"
    code, err = run_rtiow("render", "-q", "--reproducible", "--scene", "cover", "--width", 48,
                          "--spp", 6, "--seed", 7, "--passes", "albedo", "--stats-channels",
                          "-o", first)
    assert code == 0, err
    again = tmp_path / "again.exr"
    render = rtiow.render_like(str(first), output=str(again))
    assert again.read_bytes() == first.read_bytes()
    assert render.summary["seed"] == 7 and render.summary["samples"] == "6 spp"
    # The image read is never the output.
    with pytest.raises(ValueError, match="is the input file"):
        rtiow.render_like(str(first), output=str(first), spp=2)
    assert again.read_bytes() == first.read_bytes()
    # In memory too: the recorded request's pixels.
    assert np.array_equal(rtiow.render_like(str(first)).image, rtiow.read_image(str(first)))


def test_each_keyword_given_replaces_its_part(tmp_path):
    first = tmp_path / "first.png"
    scene = rtiow.builtin_scene("cover")
    rtiow.render(scene, width=40, spp=4, seed=3, output=str(first))
    more = rtiow.render_like(str(first), spp=9, sampler="independent")
    asked = rtiow.render(scene, width=40, spp=9, seed=3, sampler="independent")
    assert np.array_equal(more.image, asked.image)
    # Given a scene, it renders that scene with the image's settings.
    other = rtiow.builtin_scene("materials")
    moved = rtiow.render_like(str(first), scene=other)
    assert moved.summary["scene"] == "materials" and moved.image.shape[1] == 40


def test_a_scene_file_edited_since_is_refused(run_rtiow, tmp_path):
    scene_file = tmp_path / "balls.json"
    code, err = run_rtiow("scene", "spheres:20", "-o", scene_file)
    assert code == 0, err
    image = tmp_path / "balls.exr"
    code, err = run_rtiow("render", "-q", scene_file, "--width", 32, "--spp", 2, "-o", image)
    assert code == 0, err
    assert rtiow.render_like(str(image)).image.shape == (21, 32, 3)
    edited = json.loads(scene_file.read_text())
    edited["spheres"][-1]["radius"] *= 1.5
    scene_file.write_text(json.dumps(edited))
    with pytest.raises(ValueError, match="like image"):
        rtiow.render_like(str(image))


def test_an_image_that_records_no_request_is_refused(tmp_path):
    plain = tmp_path / "plain.png"
    rtiow.render(rtiow.builtin_scene("cover"), width=16, spp=1).write(str(plain))
    stripped = tmp_path / "stripped.png"
    data = plain.read_bytes()
    # PNG without its text chunks: keep the signature, IHDR, IDAT and IEND only.
    out, at = data[:8], 8
    while at < len(data):
        length = int.from_bytes(data[at:at + 4], "big")
        kind = data[at + 4:at + 8]
        if kind in (b"IHDR", b"IDAT", b"IEND"):
            out += data[at:at + 12 + length]
        at += 12 + length
    stripped.write_bytes(out)
    with pytest.raises(ValueError, match="like image"):
        rtiow.render_like(str(stripped))
    with pytest.raises(ValueError, match="no option 'sppp'"):
        rtiow.render_like(str(plain), sppp=3)
