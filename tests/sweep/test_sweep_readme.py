"""The README's sweep example runs as written (it is tiny: 2 runs of 0.5 s, 64×48 clips)."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

README = Path(__file__).resolve().parents[2] / "README.md"


def test_the_readme_sweep_example_runs_as_written(tmp_path):
    section = README.read_text().split("## Sweeps and data sets", 1)[1].split("\n## ", 1)[0]
    [block] = re.findall(r"```python\n(.*?)```", section, flags=re.S)
    # As a script, the way a user runs it (the pool's workers do not run the script again).
    (tmp_path / "example.py").write_text(block)
    result = subprocess.run([sys.executable, "example.py"], cwd=tmp_path, capture_output=True,
                            text=True, timeout=300, check=False)
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert lines[0].startswith("sweep done: 2 runs executed")
    assert [line.split()[:2] for line in lines[1:]] == [["0.2", "(15,"], ["0.8", "(15,"]]
    assert all(line.endswith("clip.mp4") for line in lines[1:])
    assert (tmp_path / "pit_sweep" / "index.csv").exists()
