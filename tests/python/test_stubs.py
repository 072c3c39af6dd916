"""The type stubs (python/rtiow/_rtiow.pyi) are the module's: mypy's stubtest finds every public
name of the compiled module in them and nothing else, each function's parameters are the
module's (pybind11's signature lines; render()'s keywords each taken by it), and docs/python.md's examples type-check
against them as a user's editor would check a script (a slip such as widht= is an error there,
before it runs: the page's one deliberate slip says so in its comment)."""

import ast
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

SOURCE = Path(os.environ["RTIOW_SOURCE_DIR"])
pytest.importorskip("mypy", reason="mypy (Debian's mypy package) checks the stubs")

import rtiow  # noqa: E402  (after the skip: the module is only needed where mypy is)
import rtiow._rtiow  # noqa: E402


def run(args, cwd):
    done = subprocess.run([sys.executable, "-m", *args], cwd=cwd, capture_output=True, text=True,
                          timeout=300, check=False)
    return done.returncode, done.stdout + done.stderr


def test_the_stubs_name_what_the_module_has(tmp_path):
    allowlist = SOURCE / "tests" / "python" / "stubtest_allowlist.txt"
    code, out = run(["mypy.stubtest", "rtiow", "--allowlist", str(allowlist)], tmp_path)
    assert code == 0, out


def test_the_pages_examples_type_check_against_the_stubs(tmp_path):
    page = (SOURCE / "docs" / "python.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", page, re.S)
    script = tmp_path / "examples.py"
    script.write_text("\n".join(blocks))
    code, out = run(["mypy", "--no-incremental", "--cache-dir", os.devnull,
                     "--check-untyped-defs", "--ignore-missing-imports", str(script)], tmp_path)
    assert code == 0, out


def stub_functions():
    """Each function of the stubs: its parameters' names in order and their kinds."""
    tree = ast.parse((Path(rtiow._rtiow.__file__).parent / "_rtiow.pyi").read_text())
    found = {}
    for node in tree.body:
        if isinstance(node, ast.FunctionDef):
            a = node.args
            found[node.name] = ([p.arg for p in a.posonlyargs + a.args],
                                [p.arg for p in a.kwonlyargs])
    return found


def runtime_parameters(function):
    """pybind11 states a function's signature on its docstring's first line."""
    line = function.__doc__.splitlines()[0]
    inside = line[line.index("(") + 1:line.rindex(") ->")]
    positional, keywords, seen_star = [], [], False
    for part in (p.strip() for p in inside.split(",") if p.strip()):
        if part == "*":
            seen_star = True
        elif not part.startswith("**"):
            (keywords if seen_star else positional).append(part.split(":")[0].strip())
    return positional, keywords


def test_every_stub_functions_parameters_are_the_modules():
    stubs = stub_functions()
    assert set(stubs) >= {"render", "diff", "merge", "read_image", "builtin_scene", "scene"}
    for name, (positional, keywords) in stubs.items():
        runtime_positional, runtime_keywords = runtime_parameters(getattr(rtiow._rtiow, name))
        assert positional == runtime_positional, name
        if name in ("render", "render_like"):  # then their **options: below
            assert keywords[:len(runtime_keywords)] == runtime_keywords, name
        else:
            assert keywords == runtime_keywords, name
    # Each keyword the stub gives render() is one it takes: a wrong value is refused by that
    # name, never as an option it does not have.
    scene = rtiow.builtin_scene("cover")
    assert stubs["render_like"][1][2:] == stubs["render"][1][1:]  # the same options
    for keyword in stubs["render"][1]:
        if keyword == "progress":
            continue
        with pytest.raises(ValueError) as refused:
            rtiow.render(scene, **{"width": 8, "spp": 1, keyword: object()})
        assert "has no option" not in str(refused.value), keyword
        assert keyword in str(refused.value), (keyword, str(refused.value))
