"""A render to a file from Python is the library's session, as rtiow render -o runs it: the same
bytes as the command line (every channel: spp, variances, passes), a checkpoint that keeps a
render stopped by Ctrl-C and continues it with resume=True to the uninterrupted render's bytes,
and the session's options refused where they cannot apply."""

import json
import os

import pytest

import rtiow

MODES = [
    {"spp": 4},
    {"spp": 4, "stats_channels": True, "passes": "albedo,normal,depth"},
    {"spp": 32, "adaptive": True, "stats_channels": True},
    {"spp": 64, "image_error": 0.2, "passes": "depth"},
    {"spp": 4, "crop": "8,4,40,20", "passes": "normal"},
]


def cli_words(options):
    words = []
    for name, value in options.items():
        flag = "--" + name.replace("_", "-")
        words += [flag] if value is True else [flag, str(value)]
    return words


@pytest.mark.parametrize("options", MODES, ids=lambda o: ",".join(f"{k}={v}" for k, v in o.items()))
def test_the_summary_is_what_summary_json_says(options, run_rtiow, tmp_path):
    summary = tmp_path / "cli.json"
    code, err = run_rtiow("render", "-q", "--scene", "cover", "--width", 48, *cli_words(options),
                          "-o", tmp_path / "cli.exr", "--summary-json", summary)
    assert code == 0, err
    cli = json.loads(summary.read_text())
    render = rtiow.render(rtiow.builtin_scene("cover"), width=48, **options)
    timed = {"render_seconds", "judging_seconds", "build_seconds", "mrays_per_second"}
    head = {"schema", "version", "command", "exit_code", "seconds"}
    assert set(render.summary) == set(cli) - head
    for key in set(render.summary) - timed - {"output"}:
        assert render.summary[key] == cli[key], key
    assert render.summary["output"] is None


@pytest.mark.parametrize("options", MODES, ids=lambda o: ",".join(f"{k}={v}" for k, v in o.items()))
def test_a_render_to_a_file_is_the_command_lines_file_byte_for_byte(options, run_rtiow, tmp_path):
    cli = tmp_path / "cli.exr"
    code, err = run_rtiow("render", "-q", "--reproducible", "--scene", "cover", "--width", 48,
                          *cli_words(options), "-o", cli)
    assert code == 0, err
    scene = rtiow.builtin_scene("cover")
    to_file = tmp_path / "session.exr"
    render = rtiow.render(scene, width=48, output=str(to_file), reproducible=True, **options)
    assert render.summary["output"] == str(to_file)
    assert to_file.read_bytes() == cli.read_bytes()
    # A render in memory written afterwards is the same file.
    written = tmp_path / "written.exr"
    rtiow.render(scene, width=48, **options).write(str(written), reproducible=True)
    assert written.read_bytes() == cli.read_bytes()
    # Nothing is left beside the output: no lock, no checkpoint of a finished render.
    assert sorted(os.listdir(tmp_path)) == ["cli.exr", "session.exr", "written.exr"]


def test_ctrl_c_keeps_the_render_and_resume_finishes_it_as_one_render(tmp_path):
    scene = rtiow.builtin_scene("cover")
    options = {"width": 64, "spp": 3000, "checkpoint": 0.05, "reproducible": True}
    out = tmp_path / "stopped.exr"

    def interrupt_once_started(fraction):
        if 0.0 < fraction < 0.5:  # as Ctrl-C would, from the caller's thread
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt) as stopped:
        rtiow.render(scene, output=str(out), progress=interrupt_once_started, **options)
    checkpoint = tmp_path / "stopped.exr.rtiow-checkpoint"
    assert checkpoint.exists()
    notes = " ".join(getattr(stopped.value, "__notes__", []))
    assert "stopped.exr.rtiow-checkpoint" in notes and "resume" in notes
    # Continued, it is the render nothing stopped, byte for byte, and its checkpoint is gone.
    resumed = rtiow.render(scene, output=str(out), resume=True, **options)
    assert resumed.summary["samples"] == "3000 spp"
    whole = tmp_path / "whole.exr"
    rtiow.render(scene, output=str(whole), **options)
    assert out.read_bytes() == whole.read_bytes()
    assert not checkpoint.exists()


def test_a_callback_that_raises_after_the_render_is_whole_loses_nothing(tmp_path):
    out = tmp_path / "whole.exr"

    def refuse_the_end(fraction):
        if fraction == 1.0:
            raise RuntimeError("the caller's own failure")

    with pytest.raises(RuntimeError, match="the caller's own failure"):
        rtiow.render(rtiow.builtin_scene("cover"), width=32, spp=2, output=str(out),
                     progress=refuse_the_end)
    assert out.exists()  # the finished render was written before the exception went on
    assert not (tmp_path / "whole.exr.rtiow-checkpoint").exists()


def test_a_checkpoint_is_refused_unless_told_what_to_do_with_it(tmp_path):
    scene = rtiow.builtin_scene("cover")
    out = tmp_path / "kept.exr"
    rtiow.render(scene, width=32, spp=2, output=str(out), keep_state=True)
    assert (tmp_path / "kept.exr.rtiow-checkpoint").exists()
    with pytest.raises(ValueError, match="resume.*restart"):
        rtiow.render(scene, width=32, spp=4, output=str(out))
    # A checkpoint of another render is not continued.
    with pytest.raises(ValueError, match="another render"):
        rtiow.render(scene, width=40, spp=4, output=str(out), resume=True)
    # restart discards it and renders anew.
    rtiow.render(scene, width=32, spp=4, output=str(out), restart=True)
    assert not (tmp_path / "kept.exr.rtiow-checkpoint").exists()


@pytest.mark.parametrize("options, words", [
    ({"resume": True}, "resume is for a render to a file: give output"),
    ({"keep_state": True}, "keep_state is for a render to a file"),
    ({"preview": 1.0}, "preview is for a render to a file"),
    ({"display": "localhost:14158"}, "display is for a render to a file"),
    ({"output": "x.exr", "resume": True, "restart": True}, "give resume or restart, not both"),
    ({"output": "x.exr", "keep_state": True, "checkpoint": 0},
     "keep_state keeps the render's checkpoint: it needs checkpoint above 0"),
    ({"output": "x.exr", "preview": 1.0, "part": "0/2"}, "preview shows a whole render"),
    ({"output": "x.png", "part": "0/2"}, "must be .exr"),
    ({"output": 3}, "output=3: expected a string"),
])
def test_the_sessions_options_are_refused_where_they_cannot_apply(options, words, tmp_path,
                                                                   monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(ValueError, match=words):
        rtiow.render(rtiow.builtin_scene("cover"), width=16, spp=2, **options)
    assert os.listdir(tmp_path) == []
