"""Every Python block of the README runs as written."""

import re

from conftest import ROOT


def test_every_python_block_of_the_readme_runs(capsys):
    readme = (ROOT / "README.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", readme, re.DOTALL)
    assert blocks, "the README has a Python example"
    for block in blocks:
        exec(compile(block, "README.md", "exec"), {})
    assert "(1000001,) (1000001, 2) (1000001, 2, 2)" in capsys.readouterr().out
