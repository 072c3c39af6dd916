"""rtiow.render() gives the command line's pixels for the same request, float for float, in every
sampler and mode (determinism is the point here: exact equality is asked)."""

import numpy as np
import pytest

import rtiow

CASES = [
    {"sampler": "independent", "spp": 8},
    {"sampler": "sobol", "spp": 8},
    {"sampler": "padded-sobol", "spp": 8},
    {"sampler": "sobol", "spp": 8, "roulette": "off", "depth": 5},
    {"image_error": 0.2, "spp": 64},
    {"image_error": 0.2, "denoise": True},
    {"target_error": 0.3, "spp": 64},
    {"adaptive": True, "spp": 32},
    {"spp": 4, "crop": "8,4,40,20"},
    {"spp": 4, "stats_channels": True},
    {"spp": 4, "lookfrom": "3,2,3", "vfov": 40.0, "aperture": 0.2},
]


def cli_words(options):
    words = []
    for name, value in options.items():
        flag = "--" + name.replace("_", "-")
        if value is True:
            words.append(flag)
        else:
            words += [flag, str(value)]
    return words


@pytest.mark.parametrize("options", CASES, ids=lambda o: ",".join(f"{k}={v}" for k, v in o.items()))
def test_render_gives_the_command_lines_pixels(options, run_rtiow, tmp_path):
    out = tmp_path / "cli.exr"
    code, err = run_rtiow("render", "-q", "--scene", "cover", "--width", 48,
                          *cli_words(options), "-o", out)
    assert code == 0, err
    render = rtiow.render(rtiow.builtin_scene("cover"), width=48, **options)
    from_file = rtiow.read_image(str(out))
    assert render.image.shape == from_file.shape
    assert np.array_equal(render.image, from_file)


def test_a_scene_file_renders_as_the_command_line_renders_it(run_rtiow, tmp_path):
    scene_file = tmp_path / "spheres.json"
    code, err = run_rtiow("scene", "spheres:300", "-o", scene_file)
    assert code == 0, err
    out = tmp_path / "cli.exr"
    code, err = run_rtiow("render", "-q", scene_file, "--width", 40, "--spp", 4, "-o", out)
    assert code == 0, err
    render = rtiow.render(rtiow.load_scene(str(scene_file)), width=40, spp=4)
    assert np.array_equal(render.image, rtiow.read_image(str(out)))


def test_the_passes_counts_and_variances_are_the_command_lines_channels(run_rtiow, tmp_path):
    out = tmp_path / "cli.exr"
    code, err = run_rtiow("render", "-q", "--scene", "cover", "--width", 48, "--spp", 6,
                          "--passes", "albedo,normal,depth", "--stats-channels", "-o", out)
    assert code == 0, err
    render = rtiow.render(rtiow.builtin_scene("cover"), width=48, spp=6,
                          passes="albedo,normal,depth", stats_channels=True)
    channels = rtiow.read_channels(str(out))
    statistics = {"R", "G", "B", "spp", "variance.R", "variance.G", "variance.B"}
    assert sorted(render.passes) == sorted(set(channels) - statistics)
    for name, values in render.passes.items():
        assert np.array_equal(values, channels[name]), name
    assert np.array_equal(render.spp.astype(np.float32), channels["spp"])
    for c, name in enumerate("RGB"):
        assert np.array_equal(render.variance[..., c], channels["variance." + name]), name
