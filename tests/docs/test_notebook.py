"""The cookbook notebook (docs/cookbook.ipynb) runs top to bottom.

Its cells assert the physics they describe, so executing it tests the notebook and the engine
together. It runs in a real Jupyter kernel (ipykernel through nbclient) on this interpreter,
importing the same pointmass as this test process (the checkout's ``src`` when run with
``PYTHONPATH=src``), so a stale installed copy can never be what passes.

Without the ``notebook`` extra or EGL the execution test skips, except under
``POINTMASS_REQUIRE_GL=1`` (CI, scripts/test.sh), where that is a failure naming what to install.
"""

from __future__ import annotations

import json
import os
import sys
from pathlib import Path

import pytest

import pointmass

ROOT = Path(__file__).resolve().parents[2]
NOTEBOOK = ROOT / "docs" / "cookbook.ipynb"
#: The stored notebook (with its plots and clip) must stay light enough to read on GitHub: its
#: eight plots are drawn 400–560 px wide to be readable (20–70 kB each; 386 kB in all).
MAX_BYTES = 450_000
KERNEL = "pointmass-notebook-test"


def _required() -> bool:
    return os.environ.get("POINTMASS_REQUIRE_GL", "") not in ("", "0")


def _skip_or_fail(message: str) -> None:
    if _required():
        pytest.fail(f"POINTMASS_REQUIRE_GL=1 but {message}")
    pytest.skip(message)


@pytest.fixture
def nbclient():
    """nbclient, or a skip (a failure under POINTMASS_REQUIRE_GL=1) naming the extra."""
    try:
        import ipykernel  # noqa: F401  (the kernel the notebook runs in)
        import matplotlib  # noqa: F401
        import nbclient
        import nbformat  # noqa: F401
    except ImportError as exc:
        _skip_or_fail(f'the notebook test needs the notebook extra ({exc}): '
                      f'pip install "pointmass[notebook]"')
    return nbclient


@pytest.fixture
def egl():
    """The notebook records a clip offscreen: skip without EGL (fail when required)."""
    try:
        from pointmass.render import create_headless_context

        create_headless_context().release()
    except Exception as exc:  # ImportError (no render extra) or RenderUnavailable
        _skip_or_fail(f"no EGL OpenGL context for the notebook's clip: {exc}")


def _kernel_manager(tmp_path: Path):
    """A kernel on this very interpreter: a kernelspec of our own, so a user-wide "python3"
    kernelspec pointing at another Python cannot be picked up instead."""
    from ipykernel.kernelspec import write_kernel_spec
    from jupyter_client.kernelspec import KernelSpecManager
    from jupyter_client.manager import KernelManager

    kernels = tmp_path / "kernels"
    write_kernel_spec(kernels / KERNEL)
    specs = KernelSpecManager(kernel_dirs=[str(kernels)], ensure_native_kernel=False)
    return KernelManager(kernel_name=KERNEL, kernel_spec_manager=specs)


def _kernel_env() -> dict[str, str]:
    """This environment, with the folder this process imports pointmass from put first on the
    kernel's path, and matplotlib left to the kernel's inline backend (as in Jupyter)."""
    src = str(Path(pointmass.__file__).resolve().parents[1])
    env = dict(os.environ)
    env.pop("MPLBACKEND", None)
    env["PYTHONPATH"] = os.pathsep.join([src, *filter(None, [env.get("PYTHONPATH")])])
    return env


@pytest.mark.gl
@pytest.mark.slow
def test_the_cookbook_notebook_runs_top_to_bottom(nbclient, egl, tmp_path):
    import nbformat

    nb = nbformat.read(NOTEBOOK, as_version=4)
    # One more cell, in the kernel: which interpreter and which pointmass it ran.
    nb.cells.append(nbformat.v4.new_code_cell(
        "import sys, pointmass\nprint(sys.executable)\nprint(pointmass.__file__)"))
    client = nbclient.NotebookClient(
        nb, km=_kernel_manager(tmp_path), timeout=300, startup_timeout=120,
        resources={"metadata": {"path": str(NOTEBOOK.parent)}})
    client.execute(env=_kernel_env())  # raises CellExecutionError naming the failing cell

    errors = [out for cell in nb.cells for out in cell.get("outputs", [])
              if out.output_type == "error"]
    assert not errors
    executable, module = nb.cells[-1].outputs[0].text.split()
    assert Path(executable) == Path(sys.executable)
    assert Path(module).resolve() == Path(pointmass.__file__).resolve()
    # Every plot and the clip was shown (a cell that silently showed nothing passes otherwise).
    shown = [out for cell in nb.cells for out in cell.get("outputs", [])
             if out.output_type in ("display_data", "execute_result")]
    assert sum("image/png" in out.data for out in shown) >= 8
    assert any("<video" in out.data.get("text/html", "") for out in shown)


def test_the_stored_notebook_is_small_and_shows_no_errors():
    """It is read on GitHub with its stored outputs: keep it light, and never commit a run that
    failed."""
    size = NOTEBOOK.stat().st_size
    assert size < MAX_BYTES, f"{NOTEBOOK.name} is {size / 1000:.0f} kB (at most {MAX_BYTES})"
    cells = json.loads(NOTEBOOK.read_text(encoding="utf-8"))["cells"]
    code = [cell for cell in cells if cell["cell_type"] == "code"]
    assert code, "no code cells"
    failed = [out.get("ename") for cell in code for out in cell.get("outputs", [])
              if out["output_type"] == "error"]
    assert not failed, f"the stored notebook shows errors: {failed}"
