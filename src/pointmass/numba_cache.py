"""Where numba keeps the compiled kernels: a per-user cache folder, set before numba loads.

numba's default (``cache=True``) writes beside the source, in ``pointmass/__pycache__``; an
installed package's folder is often read-only (a system or shared site-packages), and numba then
recompiles every kernel on every run (about a minute). Instead ``NUMBA_CACHE_DIR`` is set, when
the user has not set it, to ``$XDG_CACHE_HOME/pointmass/numba`` (``~/.cache/pointmass/numba``;
``POINTMASS_CACHE_DIR`` replaces ``$XDG_CACHE_HOME/pointmass``). Importing this module does
it; ``pointmass/__init__`` imports it before anything that imports numba.

Checkouts do not collide: numba files each source folder's kernels under a sub-folder named by
the folder's path and its SHA-1 (``numba.core.caching._CacheLocator.get_suitable_cache_subpath``).

Stale kernels: numba checks only the stamp of the file that defines a kernel, not of the files
whose functions it calls and inlines (a kernel in ``rigid/step.py`` kept calling the old
``integrate.free_rotation`` after that file changed, until its cache files were deleted). So the
folder is one per version of the package's sources: ``.../numba/<digest>``, the digest of every
``.py`` file's name and contents (about 1 MB, a few ms at import). Any change to the sources
(an edit, a merge, an upgrade) compiles afresh instead of mixing old and new code.
"""

from __future__ import annotations

import hashlib
import os
import sys
from pathlib import Path

#: The environment variable numba reads (at import) for its cache folder.
NUMBA_VARIABLE = "NUMBA_CACHE_DIR"


def default_cache_dir() -> Path:
    """``$POINTMASS_CACHE_DIR/numba``, else the platform's per-user cache folder +
    ``pointmass/numba``."""
    own = os.environ.get("POINTMASS_CACHE_DIR")
    if own:
        return Path(own).expanduser() / "numba"
    if sys.platform == "win32":
        base = Path(os.environ.get("LOCALAPPDATA") or Path.home() / "AppData" / "Local")
    elif sys.platform == "darwin":
        base = Path.home() / "Library" / "Caches"
    else:
        base = Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache")
    return base / "pointmass" / "numba"


def source_digest(package: Path | None = None) -> str:
    """A short digest of the package's Python sources (names and contents), which names the
    cache folder of this version of them."""
    package = package or Path(__file__).resolve().parent
    digest = hashlib.sha1()
    for path in sorted(package.rglob("*.py")):
        digest.update(str(path.relative_to(package)).encode())
        digest.update(path.read_bytes())
    return digest.hexdigest()[:16]


def configure() -> Path | None:
    """Point numba at the per-user cache (the folder of this version of the sources) unless the
    user chose a folder already; returns the folder in use (None: numba's own default, when
    ours cannot be created)."""
    chosen = os.environ.get(NUMBA_VARIABLE)
    if chosen:
        return Path(chosen)
    path = default_cache_dir() / source_digest()
    try:
        path.mkdir(parents=True, exist_ok=True)
    except OSError:
        return None  # a read-only home: numba falls back to __pycache__ or its own folder
    if not os.access(path, os.W_OK | os.X_OK):
        return None
    os.environ[NUMBA_VARIABLE] = str(path)
    numba = sys.modules.get("numba")
    if numba is not None:  # imported before pointmass: its config already read the variable
        numba.config.CACHE_DIR = str(path)
    return path


def cache_dir() -> Path | None:
    """The folder numba caches kernels in now (None: beside the sources)."""
    import numba

    return Path(numba.config.CACHE_DIR) if numba.config.CACHE_DIR else None


configure()
