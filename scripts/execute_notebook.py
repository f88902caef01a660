"""Run a notebook top to bottom and store its outputs in place (docs/cookbook.ipynb by default).

The stored outputs are what GitHub shows, so refresh them after changing the notebook or the
physics it shows: ``.venv/bin/python scripts/execute_notebook.py``. The kernel runs on this
interpreter with this checkout's ``src`` first on its path; outputs carry no timings and
consecutive prints are merged, so a run with nothing changed rewrites the same file.
Needs the ``notebook`` and ``render`` extras and EGL (the clip).
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def execute(path: Path) -> None:
    import nbclient
    import nbformat
    from ipykernel.kernelspec import write_kernel_spec
    from jupyter_client.kernelspec import KernelSpecManager
    from jupyter_client.manager import KernelManager

    nb = nbformat.read(path, as_version=4)
    kernelspec = nb.metadata.get("kernelspec")
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(ROOT / "src"), env.get("PYTHONPATH")]))
    env.pop("MPLBACKEND", None)  # the kernel's inline backend, as in Jupyter
    with tempfile.TemporaryDirectory() as tmp:
        # A kernelspec of our own: this interpreter, whatever "python3" means elsewhere.
        write_kernel_spec(Path(tmp) / "here")
        specs = KernelSpecManager(kernel_dirs=[tmp], ensure_native_kernel=False)
        client = nbclient.NotebookClient(
            nb, km=KernelManager(kernel_name="here", kernel_spec_manager=specs), timeout=600,
            record_timing=False, resources={"metadata": {"path": str(path.parent.resolve())}})
        client.execute(env=env)
    for cell in nb.cells:
        if cell.cell_type == "code":
            cell.outputs = _merge_streams(cell.outputs)
    if kernelspec is not None:
        nb.metadata["kernelspec"] = kernelspec  # keep the notebook's own ("python3")
    nbformat.write(nb, path)


def _merge_streams(outputs: list) -> list:
    """Consecutive prints to the same stream as one output (nbclient splits them by timing)."""
    merged: list = []
    for out in outputs:
        last = merged[-1] if merged else None
        if (last is not None and out.output_type == last.output_type == "stream"
                and out.name == last.name):
            last.text += out.text
        else:
            merged.append(out)
    return merged


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("notebook", nargs="?", type=Path, default=ROOT / "docs" / "cookbook.ipynb")
    args = parser.parse_args(argv)
    execute(args.notebook)
    size = args.notebook.stat().st_size
    print(f"wrote {args.notebook} ({size / 1000:.0f} kB)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
