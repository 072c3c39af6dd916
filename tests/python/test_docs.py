"""docs/python.md's examples run as written: every ```python block, in order, in a scratch
directory (each block's assertions are what the page promises)."""

import os
import re
from pathlib import Path

import pytest

PAGE = Path(os.environ["RTIOW_SOURCE_DIR"]) / "docs" / "python.md"
BLOCKS = re.findall(r"```python\n(.*?)```", PAGE.read_text(), re.S)


def test_the_page_has_examples():
    assert len(BLOCKS) >= 4


@pytest.mark.parametrize("index", range(len(BLOCKS)))
def test_each_example_runs(index, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    exec(compile(BLOCKS[index], f"docs/python.md block {index + 1}", "exec"), {})
