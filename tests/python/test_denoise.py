"""Denoising from Python: a render written denoised, and a render kept as parts denoised after
their merge, give the command line's pixels and report the estimated error."""

import json

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
    # threads= caps the merge and the denoiser as --threads does: the same image on any count.
    one = tmp_path / "one.exr"
    capped = rtiow.denoise(parts, str(one), threads=1)
    assert capped["estimated_error"] == figures["estimated_error"]
    assert capped["noisy_error"] == figures["noisy_error"]
    assert np.array_equal(py, rtiow.read_image(str(one)))
    with pytest.raises(ValueError, match="threads must be from 0"):
        rtiow.merge(parts, str(tmp_path / "never.exr"), threads=-1)
    assert not (tmp_path / "never.exr").exists()


def test_a_render_in_memory_is_denoised_as_the_command_line_denoises_it(run_rtiow, tmp_path):
    cli = tmp_path / "cli.exr"
    summary = tmp_path / "cli.json"
    code, err = run_rtiow("render", "-q", "--scene", "cover", "--width", 48, "--spp", 8,
                          "--denoise", "-o", cli, "--summary-json", summary)
    assert code == 0, err
    render = rtiow.render(rtiow.builtin_scene("cover"), width=48, spp=8, denoise=True)
    channels = rtiow.read_channels(str(cli))
    rgb = np.stack([channels[c] for c in "RGB"], axis=-1)
    assert np.array_equal(render.image, rgb)
    assert np.array_equal(render.noisy, np.stack([channels["noisy." + c] for c in "RGB"], -1))
    assert np.array_equal(render.denoise_mse,
                          np.stack([channels["denoise.mse." + c] for c in "RGB"], -1))
    assert not np.array_equal(render.image, render.noisy)
    reported = json.loads(summary.read_text())["denoise"]
    figures = render.summary["denoise"]
    assert figures["estimated_error"] == pytest.approx(reported["estimated_error"], rel=1e-9)
    assert figures["noisy_error"] == pytest.approx(reported["noisy_error"], rel=1e-9)
    written = tmp_path / "py.exr"
    render.write(str(written))
    again = rtiow.read_channels(str(written))
    assert sorted(again) == sorted(channels)
    for name, values in channels.items():
        assert np.array_equal(again[name], values), name


def test_a_plain_render_has_no_denoised_parts():
    render = rtiow.render(rtiow.builtin_scene("cover"), width=16, spp=4)
    assert render.noisy is None and render.denoise_mse is None
    assert render.summary["denoise"] is None


def test_denoise_refusals(tmp_path):
    with pytest.raises(ValueError, match="at least 2 spp"):
        rtiow.render(rtiow.builtin_scene("cover"), width=16, spp=1, denoise=True)
    with pytest.raises(ValueError, match="target_error"):
        rtiow.render(rtiow.builtin_scene("cover"), width=16, target_error=0.1, denoise=True)
    part = str(tmp_path / "plain.exr")
    rtiow.render(rtiow.builtin_scene("cover"), width=16, spp=4, part="0/1", output=part)
    with pytest.raises(ValueError, match="render them with denoise"):
        rtiow.denoise([part], str(tmp_path / "out.png"))


def test_denoise_reports_its_progress_and_stops_where_progress_raises(tmp_path):
    part = str(tmp_path / "p.exr")
    rtiow.render(rtiow.builtin_scene("cover"), width=800, spp=2, denoise=True, part="0/1",
                 output=part)
    seen = []
    figures = rtiow.denoise([part], str(tmp_path / "out.png"), progress=seen.append)
    assert figures["estimated_error"] > 0
    assert seen and seen[-1] == 1.0  # the last call: the image written
    assert seen == sorted(seen) and all(0.0 <= f <= 1.0 for f in seen)

    class Enough(Exception):
        pass

    def stop(fraction):
        if fraction > 0.0:  # the denoiser under way (800x533: a second on 2 cores)
            raise Enough

    stopped = tmp_path / "stopped.png"
    with pytest.raises(Enough):
        rtiow.denoise([part], str(stopped), progress=stop)
    assert not stopped.exists()
    merged = rtiow.merge([part], str(tmp_path / "m.png"), denoise=True, progress=seen.append)
    assert merged is not None and seen[-1] == 1.0


def test_a_target_cut_short_reports_the_error_of_the_image_it_delivers():
    # Wherever the time limit falls, the estimate is the denoised image's, not a judgement's of
    # fewer samples.
    render = rtiow.render(rtiow.builtin_scene("cover"), width=96, image_error=0.001,
                          denoise=True, time_limit=0.3)
    error = render.summary["error"]
    assert render.summary["stopped"].startswith("time limit")
    assert render.summary["error"]["target"] == {"kind": "denoised image", "asked": 0.001,
                                                 "reached": False}
    assert error["estimate"] == "calibrated"
    assert error["estimated"] == render.summary["denoise"]["estimated_error"]
    assert f"not reached: {error['estimated']:.3g} at " in render.summary["samples"]
