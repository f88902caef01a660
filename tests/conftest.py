"""Fixtures shared by every test folder: golden-image comparison.

Goldens live in tests/golden/ (made under Mesa llvmpipe) and are rewritten only with
POINTMASS_UPDATE_GOLDENS=1 — look at them before committing.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest

GOLDEN_DIR = Path(__file__).resolve().parent / "golden"
#: Pass when the mean absolute difference (0-255) is at most this...
GOLDEN_MEAN_TOLERANCE = 0.5
#: ...and fewer than this fraction of pixels differ by more than GOLDEN_PIXEL_THRESHOLD.
GOLDEN_FRACTION_TOLERANCE = 0.005
GOLDEN_PIXEL_THRESHOLD = 24


@pytest.fixture
def golden(request, tmp_path):
    """``golden(name, rgb)`` compares an (H, W, 3) uint8 image with tests/golden/<name>.png."""
    from PIL import Image

    def check(name: str, rgb: np.ndarray, *, mean_tol: float = GOLDEN_MEAN_TOLERANCE,
              fraction_tol: float = GOLDEN_FRACTION_TOLERANCE) -> None:
        path = GOLDEN_DIR / f"{name}.png"
        if os.environ.get("POINTMASS_UPDATE_GOLDENS") == "1":
            GOLDEN_DIR.mkdir(exist_ok=True)
            Image.fromarray(rgb).save(path)
            return
        if not path.exists():
            Image.fromarray(rgb).save(tmp_path / f"{name}-actual.png")
            pytest.fail(f"no golden {path}; run with POINTMASS_UPDATE_GOLDENS=1 to make it "
                        f"(actual image: {tmp_path / f'{name}-actual.png'})")
        want = np.asarray(Image.open(path).convert("RGB"))
        assert want.shape == rgb.shape, f"golden {path} is {want.shape}, got {rgb.shape}"
        diff = np.abs(want.astype(np.int16) - rgb.astype(np.int16))
        mean = float(diff.mean())
        fraction = float((diff.max(axis=2) > GOLDEN_PIXEL_THRESHOLD).mean())
        if mean > mean_tol or fraction >= fraction_tol:
            actual = tmp_path / f"{name}-actual.png"
            amplified = tmp_path / f"{name}-diff.png"
            Image.fromarray(rgb).save(actual)
            Image.fromarray(np.clip(diff * 4, 0, 255).astype(np.uint8)).save(amplified)
            pytest.fail(f"{name}: mean abs diff {mean:.3f} (max {mean_tol}), "
                        f"{100 * fraction:.2f}% pixels off by > {GOLDEN_PIXEL_THRESHOLD} "
                        f"(max {100 * fraction_tol:.2f}%); actual {actual}, diff {amplified}")

    return check
