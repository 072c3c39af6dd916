"""rtiow as a good citizen of Python: the GIL released while it renders, Ctrl-C raising
KeyboardInterrupt with the render stopped, a progress callback, ValueErrors with rtiow's one-line
messages, arrays over the render's own memory, docstrings."""

import os
import signal
import threading
import time

import numpy as np
import pytest

import rtiow


def interrupt_after(seconds):
    """Sends this process SIGINT (Ctrl-C) after `seconds`; the list gets the moment it was sent."""
    sent = []

    def interrupt():
        sent.append(time.monotonic())
        os.kill(os.getpid(), signal.SIGINT)

    threading.Timer(seconds, interrupt).start()
    return sent


def test_ctrl_c_stops_the_render_and_raises_keyboard_interrupt():
    scene = rtiow.builtin_scene("cover")
    sent = interrupt_after(0.5)
    with pytest.raises(KeyboardInterrupt):
        rtiow.render(scene, width=200, spp=1_000_000)
    # The render stops at its next safe point, a pass of a small image: well inside a second
    # (a render that went on would take hours).
    assert time.monotonic() - sent[0] < 5.0
    # And the module works on after it.
    assert rtiow.render(scene, width=16, spp=1).image.shape == (11, 16, 3)


def test_the_gil_is_released_while_it_renders():
    ticks = []
    rendering = threading.Event()

    def count():
        rendering.wait()
        while rendering.is_set():
            ticks.append(1)
            time.sleep(0.001)

    counter = threading.Thread(target=count)
    counter.start()
    rendering.set()
    rtiow.render(rtiow.builtin_scene("cover"), width=160, spp=16, threads=1)
    rendering.clear()
    counter.join()
    assert len(ticks) > 5


def test_progress_goes_up_to_one_and_can_stop_the_render():
    fractions = []
    rtiow.render(rtiow.builtin_scene("cover"), width=160, spp=32, threads=1,
                 progress=fractions.append)
    assert fractions and fractions[-1] == 1.0
    assert all(0.0 <= f <= 1.0 for f in fractions)
    assert fractions == sorted(fractions)

    def stop(_):
        raise RuntimeError("enough")

    with pytest.raises(RuntimeError, match="enough"):
        rtiow.render(rtiow.builtin_scene("cover"), width=200, spp=1_000_000, progress=stop)


@pytest.mark.parametrize("options, message", [
    ({"widht": 32}, "render() has no option 'widht'; did you mean width?"),
    ({"spp": -1}, "spp=-1: expected a whole number"),
    ({"spp": 2.5}, "spp=2.5: expected a whole number"),
    ({"sampler": "sobl"}, "unknown sampler 'sobl'; did you mean sobol?"),
    ({"passes": "depht"}, "passes: unknown pass 'depht'; did you mean depth?"),
    ({"adaptive": True, "image_error": 0.1}, "choose one adaptive mode"),
    ({"crop": (0, 0, 500, 5)}, "crop"),
    ({"min_spp": 4}, "min_spp=4"),
])
def test_bad_input_is_a_value_error_in_rtiows_words(options, message):
    with pytest.raises(ValueError) as refused:
        rtiow.render(rtiow.builtin_scene("cover"), width=32, **options)
    assert message in str(refused.value)
    assert "\n" not in str(refused.value)


def test_a_missing_scene_file_is_a_value_error(tmp_path):
    with pytest.raises(ValueError, match="nowhere.json"):
        rtiow.load_scene(str(tmp_path / "nowhere.json"))
    with pytest.raises(ValueError, match="unknown scene"):
        rtiow.builtin_scene("covr")


def test_arrays_are_views_of_the_render():
    render = rtiow.render(rtiow.builtin_scene("cover"), width=32, spp=2)
    image = render.image
    assert image.dtype == np.float32 and image.shape == (21, 32, 3)
    assert image.base is not None  # over the render's memory, not a copy
    assert np.shares_memory(image, render.image)
    assert render.spp.dtype == np.uint32 and (render.spp == 2).all()
    del render
    assert np.isfinite(image).all()  # the view keeps the render alive


def test_everything_public_has_a_docstring():
    for name in rtiow.__all__:
        assert getattr(rtiow, name).__doc__, name
    assert "keyword arguments" in rtiow.render.__doc__.lower() or "Keyword" in rtiow.render.__doc__


def test_ctrl_c_stops_the_denoiser_too():
    # 1200x800 at 2 spp: the render takes about a second on two cores, its denoise about 20 s.
    # The signal comes while one or the other runs; each stops within a second of it.
    sent = interrupt_after(2.0)
    with pytest.raises(KeyboardInterrupt):
        rtiow.render(rtiow.builtin_scene("cover"), width=1200, spp=2, denoise=True)
    assert time.monotonic() - sent[0] < 5.0
