"""README code blocks run, and the numbers their comments quote are what they print."""
import re
from pathlib import Path

import numpy as np

README = (Path(__file__).parents[1] / "README.md").read_text()


def test_python_blocks_run_and_quoted_numbers_hold(capsys):
    blocks = re.findall(r"```python\n(.*?)```", README, re.S)
    assert blocks
    namespace = {}
    for block in blocks:
        exec(compile(block, "README.md", "exec"), namespace)
    np.testing.assert_allclose(namespace["spectrum"].omega[:2], [336.45, 536.48], atol=0.005)
    np.testing.assert_allclose(namespace["cracked"].percent[:2], [-43.6, -7.7], atol=0.05)
    np.testing.assert_allclose(namespace["sens"].relative[:2], [0.286, 0.119], atol=5e-4)


def test_setup_commands_are_the_ones_ci_runs():
    commands = re.findall(r"```bash\n(.*?)\n```", README, re.S)
    assert commands[:2] == ['pip install ".[report,fem,render]" && hubvib run',
                            'pip install -e ".[test]" && python -m pytest']
    ci = (Path(__file__).parents[1] / ".ci" / "run").read_text()
    assert 'pip install -e ".[test]" && python -m pytest' in ci
