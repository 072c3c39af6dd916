#!/usr/bin/python3
"""Is the variance rtiow reports the variance it delivers? Renders seed pairs through the
command and prints the mean of z^2 = (a - b)^2 / (var_a + var_b) over every pixel-channel with
a variance (1 when honest), the largest z^2, and how many passed 1000.

Needs OpenImageIO's Python module (Debian: python3-openimageio).

  tests/bench/seed_pair_calibration.py build/bin/rtiow SCENE SAMPLER SPP PAIRS WIDTH

SCENE is a scene file or builtin:NAME (e.g. tests/bench/calibration-scenes/sky-lit-ground.json,
builtin:defocus). docs/accuracy.md, "Never zero where there is noise", was measured with it.
"""
import os
import subprocess
import sys
import tempfile

import numpy as np
import OpenImageIO as oiio


def render(rtiow, scene, sampler, spp, width, seed, directory):
    out = os.path.join(directory, f"seed-{seed}.exr")
    source = ["--scene", scene[len("builtin:"):]] if scene.startswith("builtin:") else [scene]
    subprocess.run([rtiow, "render", *source, "-o", out, "--spp", str(spp), "--width", str(width),
                    "--seed", str(seed), "--sampler", sampler, "--stats-channels", "-q",
                    "--checkpoint", "0"], check=True)
    image = oiio.ImageBuf(out)
    names = list(image.spec().channelnames)
    pixels = image.get_pixels(oiio.FLOAT).astype(np.float64)
    os.remove(out)
    rgb = pixels[:, :, [names.index(c) for c in "RGB"]]
    variance = pixels[:, :, [names.index("variance." + c) for c in "RGB"]]
    return rgb, variance


def main():
    rtiow, scene, sampler, spp, pairs, width = sys.argv[1:7]
    squares = []
    with tempfile.TemporaryDirectory() as directory:
        for pair in range(int(pairs)):
            a, va = render(rtiow, scene, sampler, spp, width, 2 * pair + 1, directory)
            b, vb = render(rtiow, scene, sampler, spp, width, 2 * pair + 2, directory)
            v = va + vb
            squares.append(((a - b) ** 2)[v > 0] / v[v > 0])
    z2 = np.concatenate(squares)
    print(f"{scene} {sampler} {spp} spp: mean z^2 {z2.mean():.3f}, largest {z2.max():.3g}, "
          f"above 1000: {(z2 > 1000).sum()}")


if __name__ == "__main__":
    main()
