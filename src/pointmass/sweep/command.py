"""``pointmass sweep``: the command line of ``pointmass.sweep.run``."""

from __future__ import annotations

import argparse
import importlib
import math
import re
from pathlib import Path

EPILOG = """examples:
  pointmass sweep ball_pit -o pit --set count=300 --grid restitution=0.2,0.5,0.8 --seeds 4 \\
      --seconds 2 --clip 160x120 --probes positions
  pointmass sweep bridge -o bridge --random load_mass=0:50 --grid planks=4,8 --draws 20 \\
      --probes positions
  pointmass sweep ball_pit -o pit ... --ray auto      # on the Ray cluster of `ray start`

Rerun the same command to finish a sweep that was stopped; complete runs are skipped.
The exit status is 0 when every run has a record (failed runs included: see index.csv)."""


def value(text: str):
    """A command-line value as a number, a boolean or a string."""
    text = text.strip()
    low = text.lower()
    if low in ("true", "false"):
        return low == "true"
    for kind in (int, float):
        try:
            number = kind(text)
        except ValueError:
            continue
        if isinstance(number, float) and not math.isfinite(number):
            break
        return number
    return text


def _assignment(option: str, text: str) -> tuple[str, str]:
    from ..cli import UsageError

    name, sep, rest = text.partition("=")
    if not sep or not name.strip() or not rest.strip():
        raise UsageError(f"{option} expects NAME=VALUES, got {text!r}")
    return name.strip(), rest.strip()


def parse_random(text: str):
    """``name=low:high`` (a uniform range) or ``name=a,b,c`` (choices)."""
    from ..cli import UsageError

    name, rest = _assignment("--random", text)
    if ":" in rest:
        low, _, high = rest.partition(":")
        low, high = value(low), value(high)
        if not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in (low, high)):
            raise UsageError(f"--random {name}: a range is LOW:HIGH with numbers, got {rest!r}")
        return name, (low, high)
    return name, [value(v) for v in rest.split(",")]


def parse_seeds(text: str):
    from ..cli import UsageError

    if re.fullmatch(r"\s*\d+\s*", text):
        return int(text)
    try:
        return [int(s) for s in text.split(",") if s.strip()]
    except ValueError:
        raise UsageError(f"--seeds expects a count (4) or a list (1,5,9), got {text!r}") from None


def source(text: str):
    """A demo name or path, or ``package.module:function`` for a scene function."""
    from ..cli import UsageError

    module, sep, name = text.partition(":")
    if not sep or Path(text).exists() or not re.fullmatch(r"[\w.]+", module):
        return text
    try:
        fn = getattr(importlib.import_module(module), name)
    except (ImportError, AttributeError) as exc:
        raise UsageError(f"cannot load the scene function {text!r}: {exc}") from None
    if not callable(fn):
        raise UsageError(f"{text} is not a function")
    return fn


def add_sweep_parser(sub) -> None:
    from .. import cli

    p = sub.add_parser(
        "sweep", help="run many simulations (a parameter grid, random draws, seeds) into a "
        "data set of clips and probes", epilog=EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
        description="Run a demo (or MODULE:FUNCTION building a Scene) once per combination of "
        "grid values, random draws and seeds, on every core (or a Ray cluster), keeping a clip, "
        "probes sampled at the clip's frame times and the final state of each run in "
        "OUT/runs/<run id>/, with an index table OUT/index.csv.")
    p.add_argument("source", metavar="demo",
                   help="demo name or .py path, or MODULE:FUNCTION returning a Scene")
    p.add_argument("-o", "--output", required=True, help="output folder (created; a rerun "
                   "resumes it)")
    p.add_argument("--set", dest="fixed", action="append", default=[], metavar="NAME=VALUE",
                   help="a parameter every run shares (repeatable)")
    p.add_argument("--grid", action="append", default=[], metavar="NAME=V1,V2,...",
                   help="values of a parameter; every combination is a run (repeatable)")
    p.add_argument("--random", action="append", default=[], metavar="NAME=LOW:HIGH|A,B,...",
                   help="a parameter drawn at random: uniform in [LOW, HIGH] (integers for an "
                   "integer parameter), or one of the choices (repeatable; needs --draws)")
    p.add_argument("--draws", type=cli._in_range(int, "--draws", 0, 10**6), default=0,
                   help="how many random draws (each combined with every grid point)")
    p.add_argument("--random-seed", type=int, default=0, help="seed of the draws (default 0)")
    p.add_argument("--seeds", type=str, default=None,
                   help="seeds per point: a count N (0 … N-1) or a list 1,5,9 (one seed: 7,); "
                   "given to the demo's seed parameter")
    p.add_argument("--seconds", type=cli._in_range(float, "--seconds", 0.0, cli.MAX_SECONDS,
                                                    low_open=True), default=2.0,
                   help="simulated seconds per run (default 2)")
    p.add_argument("--fps", type=cli._in_range(int, "--fps", 1, cli.MAX_FPS), default=30,
                   help="frames per second of clips and probe samples (default 30)")
    p.add_argument("--clip", metavar="WxH", default=None,
                   help="keep an mp4 of each run at this size, e.g. 160x120 (default: none)")
    p.add_argument("--probes", default="",
                   help="comma-separated probes sampled per frame: positions, velocities, "
                   "contacts, kinetic_energy, potential_energy, body_positions, "
                   "body_orientations")
    p.add_argument("--no-snapshot", action="store_true",
                   help="do not keep the final state (final.npz)")
    p.add_argument("--workers", type=cli._in_range(int, "--workers", 1, 4096), default=None,
                   help="local processes (default: every core)")
    p.add_argument("--serial", action="store_true", help="run in this process, one by one")
    p.add_argument("--ray", metavar="auto|ADDRESS", default=None,
                   help="run on a Ray cluster: auto (started here with `ray start`), local (a "
                   "private one) or HOST:PORT of its head; needs pointmass[cluster]")
    p.add_argument("--shared-folder", action="store_true",
                   help="with --ray: workers write into the output folder themselves (the same "
                   "path on every node); otherwise they send their files to this machine")
    p.add_argument("--max-retries", type=cli._in_range(int, "--max-retries", 0, 100), default=3,
                   help="times a run whose worker process died is tried again (default 3)")
    p.add_argument("--retry-failed", action="store_true",
                   help="run again the runs an earlier sweep recorded as failed")
    p.add_argument("--quiet", action="store_true", help="no progress line")
    p.set_defaults(func=cmd_sweep)


def cmd_sweep(args) -> int:
    from .. import cli
    from . import run

    if args.ray is not None and args.serial:
        raise cli.UsageError("--ray and --serial exclude each other")
    fixed = {}
    for text in args.fixed:
        name, rest = _assignment("--set", text)
        fixed[name] = value(rest)
    grid = {}
    for text in args.grid:
        name, rest = _assignment("--grid", text)
        grid[name] = [value(v) for v in rest.split(",")]
    random = dict(parse_random(t) for t in args.random)
    probes = [p.strip() for p in args.probes.split(",") if p.strip()]
    clip = cli.parse_size(args.clip) if args.clip else None
    backend = "ray" if args.ray is not None else "serial" if args.serial else "pool"
    if backend == "ray":
        from .cluster import import_ray

        import_ray()  # one line naming the extra when ray is missing
    try:
        result = run(source(args.source), args.output, seconds=args.seconds, fps=args.fps,
                     clip=clip, probes=probes, snapshot=not args.no_snapshot, fixed=fixed,
                     grid=grid, random=random, draws=args.draws, random_seed=args.random_seed,
                     seeds=parse_seeds(args.seeds) if args.seeds else None, backend=backend,
                     workers=args.workers, ray_address=args.ray, shared_folder=args.shared_folder,
                     max_retries=args.max_retries, retry_failed=args.retry_failed,
                     progress=not args.quiet)
    except (ValueError, TypeError, RuntimeError) as exc:
        raise cli.UsageError(str(exc)) from None
    except ConnectionError as exc:  # no Ray cluster where --ray points
        raise cli.Failure(str(exc)) from None
    print(result.summary())
    for run_id, error in list(result.failed.items())[:5]:
        print(f"  failed {run_id}: {error}")
    if len(result.failed) > 5:
        print(f"  ... and {len(result.failed) - 5} more (see the index's error column)")
    return 0
