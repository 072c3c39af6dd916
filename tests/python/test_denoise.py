"""Denoising from Python: a render written denoised, and a render kept as parts denoised after
their merge, give the command line's pixels and report the estimated error."""

import numpy as np
import pytest

import rtiow


def test_parts_denoise_to_the_commands_pixels(run_rtiow, tmp_path):
    scene = rtiow.builtin_scene("cover")
    parts = []
    for i, share in enumerate(["0/2", "1/2"]):
        parts.append(str(tmp_path / f"p{i}.exr"))
        rtiow.render(scene, width=48, spp=8, denoise=True, part=share, output=parts[-1])
    figures = rtiow.denoise(parts, str(tmp_path / "py.exr"))
    assert 0 < figures["estimated_error"] < figures["noisy_error"]
    code, err = run_rtiow("denoise", *parts, "-o", tmp_path / "cli.exr")
    assert code == 0, err
    py = rtiow.read_image(str(tmp_path / "py.exr"))
    assert np.array_equal(py, rtiow.read_image(str(tmp_path / "cli.exr")))
    whole = tmp_path / "whole.exr"
    rtiow.render(scene, width=48, spp=8, denoise=True, output=str(whole))
    assert np.array_equal(py, rtiow.read_image(str(whole)))


def test_denoise_is_for_a_render_to_a_file(tmp_path):
    with pytest.raises(ValueError, match="denoise"):
        rtiow.render(rtiow.builtin_scene("cover"), width=16, spp=4, denoise=True)
    part = str(tmp_path / "plain.exr")
    rtiow.render(rtiow.builtin_scene("cover"), width=16, spp=4, part="0/1", output=part)
    with pytest.raises(ValueError, match="render them with denoise"):
        rtiow.denoise([part], str(tmp_path / "out.png"))
