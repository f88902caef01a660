"""The ``pointmass`` command: list, run, render and record demos.

Every subcommand imports what it needs when it runs, so ``pointmass list`` never loads GL and
``pointmass render`` never loads pyglet. Bad input (an unknown demo, a bad ``--set``, a bad
``--size``, a parameter out of range) prints one line on stderr and exits with status 2.
"""

from __future__ import annotations

import argparse
import math
import os
import re
import signal
import sys
from pathlib import Path

from . import __version__, extras

EXIT_USAGE = 2
EXIT_FAILURE = 1


class UsageError(Exception):
    """Bad command-line input: reported in one line, exit status 2."""


class Failure(Exception):
    """Something outside the user's input went wrong (a missing extra): one line, exit 1."""


class _Parser(argparse.ArgumentParser):
    """argparse that reports errors in one line (no usage dump) with status 2."""

    def error(self, message: str):
        self.exit(EXIT_USAGE, f"{self.prog}: error: {message} (see {self.prog} --help)\n")


def parse_size(text: str) -> tuple[int, int]:
    """``"1280x720"`` → (1280, 720); each side in [16, 8192] pixels."""
    m = re.fullmatch(r"\s*(\d+)\s*[xX×]\s*(\d+)\s*", text)
    if not m:
        raise UsageError(f"--size expects WIDTHxHEIGHT such as 1280x720, got {text!r}")
    w, h = int(m[1]), int(m[2])
    if not (16 <= w <= 8192 and 16 <= h <= 8192):
        raise UsageError(f"--size sides must be in [16, 8192] pixels, got {w}x{h}")
    return w, h


#: Longest simulated time `render --time` and `record --seconds` take [s]: an hour of a demo is
#: 108 000 frames at 30 fps; past that a typo (1e9) would run for ever.
MAX_SECONDS = 3600.0
MAX_FPS = 240


def _in_range(kind: type, name: str, low: float, high: float, *, low_open: bool = False):
    """An argparse type: a finite ``kind`` in [low, high] ((low, high] with ``low_open``)."""
    def convert(text: str):
        try:
            value = kind(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{name} expects a number, got {text!r}") from None
        ok = value == value and math.isfinite(value) and value <= high and (
            value > low if low_open else value >= low)
        if not ok:
            left = "(" if low_open else "["
            raise argparse.ArgumentTypeError(
                f"{name} must be in {left}{low:g}, {high:g}], got {text!r}")
        return value
    return convert


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="pointmass", description="Mass-aggregate physics demos: list, run "
                     "in a window, render a picture or record a video.")
    parser.add_argument("--version", action="version", version=f"pointmass {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)

    p = sub.add_parser("list", help="list the demos")
    p.set_defaults(func=cmd_list)

    p = sub.add_parser("warmup", help="compile the physics kernels the demos use, once (later "
                                      "runs load them from the cache)")
    p.add_argument("demos", nargs="*", metavar="DEMO", help="only these demos (default: all)")
    p.set_defaults(func=cmd_warmup)

    def demo_args(p: argparse.ArgumentParser) -> None:
        p.add_argument("demo", help="demo name (see `pointmass list`) or path to a demo file")
        p.add_argument("--set", dest="overrides", action="append", default=[],
                       metavar="NAME=VALUE", help="set a demo parameter (repeatable)")

    p = sub.add_parser("run", help="open a window on a demo")
    demo_args(p)
    p.add_argument("--paused", action="store_true", help="start paused")
    p.set_defaults(func=cmd_run)

    p = sub.add_parser("render", help="render one picture of a demo offscreen")
    demo_args(p)
    p.add_argument("-o", "--output", required=True, help="image file (.png, .jpg)")
    p.add_argument("--time", type=_in_range(float, "--time", 0.0, MAX_SECONDS), default=0.0,
                   help="simulated seconds before the picture (default 0, at most 3600)")
    p.add_argument("--size", default="1280x720", help="WIDTHxHEIGHT pixels (default 1280x720)")
    p.add_argument("--contacts", action="store_true", help="draw contacts")
    p.add_argument("--overwrite", action="store_true", help="replace an existing file")
    p.set_defaults(func=cmd_render)

    p = sub.add_parser("record", help="record a video of a demo offscreen")
    demo_args(p)
    p.add_argument("-o", "--output", required=True,
                   help="video file (.mp4, .gif) or a folder for PNG frames")
    p.add_argument("--seconds", type=_in_range(float, "--seconds", 0.0, MAX_SECONDS,
                                                low_open=True), default=5.0,
                   help="simulated seconds to record (default 5, at most 3600)")
    p.add_argument("--fps", type=_in_range(int, "--fps", 1, MAX_FPS), default=30,
                   help="frames per simulated second (default 30, 1 to 240)")
    p.add_argument("--size", default="1280x720", help="WIDTHxHEIGHT pixels (default 1280x720)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.add_argument("--overwrite", action="store_true",
                   help="replace an existing file (or add to an existing frames folder)")
    p.set_defaults(func=cmd_record)

    from .sweep.command import add_sweep_parser  # the sweep's options live with the sweep
    add_sweep_parser(sub)
    return parser


def _simulation(args):
    """Load the demo and apply ``--set``; bad names and values become UsageError. Built in the
    physics worker (a build may compile kernels; Ctrl-C stays prompt, see ``worker``)."""
    from . import worker
    from .simulation import Simulation

    try:
        return worker.call(Simulation, args.demo, overrides=args.overrides)
    except ValueError as exc:
        raise UsageError(str(exc)) from None


def cmd_warmup(args) -> int:
    from .demo import load_demo
    from .warmup import warm

    for name in args.demos:
        try:
            load_demo(name)
        except ValueError as exc:
            raise UsageError(str(exc)) from None
    warm(args.demos or None)
    return 0


def cmd_list(args) -> int:
    from .demo import list_demos

    demos = list_demos()
    if not demos:
        print("no demos found")
        return 0
    width = max(len(d.name) for d in demos)
    title_width = max(len(d.title) for d in demos)
    for d in demos:
        desc = d.description if d.description != d.title else ""
        print(f"{d.name:<{width}}  {d.title:<{title_width}}  {desc}".rstrip())
    return 0


def has_display() -> bool:
    """False on Linux without DISPLAY or WAYLAND_DISPLAY (other systems: assume one)."""
    if not sys.platform.startswith("linux"):
        return True
    return bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))


def cmd_run(args) -> int:
    sim = _simulation(args)  # loaded and built once; bad names and --set values fail here
    if not has_display():
        # Checked before pyglet is imported: importing it with no display raises. The advice
        # fits what is installed: `record` only works with the render extra.
        record = (f"record a video instead with `pointmass record {args.demo} -o clip.mp4`"
                  if extras.has("render") else
                  'install the render extra to record videos instead (pip install '
                  '"pointmass[render]")')
        raise UsageError(
            f"no display (neither DISPLAY nor WAYLAND_DISPLAY is set): {record}, or run under "
            f"a virtual display: `xvfb-run -a pointmass run {args.demo}`")
    extras.require("viewer", "pointmass run (a window)")
    from .app import run_demo
    run_demo(sim, paused=args.paused)
    return 0


def _refuse_overwrite(output: str, overwrite: bool, *, folder_ok: bool = False) -> None:
    """Existing outputs are replaced only with --overwrite (nothing is lost by a typo)."""
    path = Path(output)
    if path.is_dir() and not folder_ok:
        raise UsageError(f"{output} is a folder; give a file name (or a new folder for PNG "
                         "frames)")
    if path.exists() and not overwrite:
        raise UsageError(f"{output} exists; pass --overwrite to replace it")


def cmd_render(args) -> int:
    extras.require("render", "pointmass render")
    from .render.snapshot import check_writable

    size = parse_size(args.size)
    _refuse_overwrite(args.output, args.overwrite)
    out = _checked_output(args.output, check_writable)
    if out.suffix.lower() not in (".png", ".jpg", ".jpeg", ".bmp", ".tif", ".tiff", ".webp"):
        raise UsageError(f"-o must name an image file (.png, .jpg), got {args.output!r}")
    sim = _simulation(args)

    from .render.snapshot import render_frame, save_image

    try:  # stepped here, not in render_frame, so a demo that fails says so in one line
        if args.time > 0:
            sim.advance(args.time)
    except (KeyboardInterrupt, Terminated):
        raise
    except Exception as exc:  # as ``record`` reports it: one line, status 1
        raise Failure(f"rendering stopped by {type(exc).__name__} at t = {sim.time:.3f} s of "
                      f"--time {args.time:g}: {exc}; no picture was written") from None
    rgb = render_frame(sim, size, show_contacts=args.contacts)
    save_image(rgb, out)
    print(f"wrote {out} ({size[0]}x{size[1]}, t = {sim.time:.3f} s)")
    return 0


def cmd_record(args) -> int:
    extras.require("render", "pointmass record")
    from .render import recording
    from .render.video import output_kind

    size = parse_size(args.size)
    try:
        frames_folder = output_kind(args.output) == "png-folder"
    except ValueError as exc:
        raise UsageError(str(exc)) from None
    if Path(args.output).is_dir() and Path(args.output).suffix:  # x.mp4/ got PNG frames
        raise UsageError(f"{args.output} is a folder, not a video file; remove it or choose "
                         "another name")
    _refuse_overwrite(args.output, args.overwrite, folder_ok=frames_folder)
    try:
        target = recording.open_target(args.output, size, args.fps)
    except (PermissionError, FileNotFoundError, ValueError) as exc:
        raise UsageError(str(exc)) from None
    try:
        sim = _simulation(args)
    except BaseException:
        target.abort()
        raise
    try:
        result = recording.record(sim, target, seconds=args.seconds, fps=args.fps, size=size,
                                  progress=not args.quiet)
    except (KeyboardInterrupt, Terminated):
        raise
    except Exception as exc:  # the demo or the disk failed: the file so far is closed, playable
        raise Failure(f"recording stopped by {type(exc).__name__}: {exc}; the frames "
                      f"recorded so far are in {args.output}") from None
    print(result.summary())
    return 0 if result.complete else EXIT_FAILURE


class Terminated(KeyboardInterrupt):
    """SIGTERM or SIGHUP (a closed ssh session): handled like Ctrl-C, so a recording closes
    its file before the process ends."""


#: The signals this command has received (``_on_signal``, ``_on_interrupt``).
_received: list[int] = []


def _on_signal(signum, frame) -> None:
    _received.append(signum)
    raise Terminated(signal.Signals(signum).name)


def _on_interrupt(signum, frame) -> None:
    """Ctrl-C, as Python's own handler (KeyboardInterrupt), noted first."""
    _received.append(signum)
    raise KeyboardInterrupt


def _handle_termination() -> None:
    _received.clear()
    for name in ("SIGTERM", "SIGHUP"):
        if hasattr(signal, name):
            signal.signal(getattr(signal, name), _on_signal)
    if signal.getsignal(signal.SIGINT) is signal.default_int_handler:
        signal.signal(signal.SIGINT, _on_interrupt)


def _interrupted_status() -> int | None:
    """The exit status of the signal this command received (130 Ctrl-C, 143 the others), if
    any. An interrupt that lands in a C callback (llvmlite's, while numba compiles) is printed
    and dropped there, and what fails next is its consequence, not a fault of its own."""
    if not _received:
        return None
    return 130 if _received[-1] == signal.SIGINT else 143


def _checked_output(path: str, check) -> Path:
    try:
        return check(path)
    except (PermissionError, FileNotFoundError) as exc:
        raise UsageError(str(exc)) from None


#: Subcommands that step physics: they say so on stderr while numba compiles.
_COMPILING_COMMANDS = ("run", "render", "record", "warmup")


def main(argv: list[str] | None = None) -> int:
    """Run the command line; returns the exit status."""
    args = build_parser().parse_args(argv)
    _handle_termination()
    status = _dispatch(args)
    from . import worker

    if worker.busy():
        # Interrupted while the physics worker still compiles or steps: nothing of it is
        # wanted, and interpreter shutdown could wait on it. Leave now (files are closed).
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(status)
    return status


def _dispatch(args) -> int:
    from .compiling import TerminalNotice

    notice = TerminalNotice() if args.command in _COMPILING_COMMANDS else None
    try:
        if notice is not None:
            with notice:
                return args.func(args)
        return args.func(args)
    except UsageError as exc:
        print(f"pointmass: error: {exc}", file=sys.stderr)
        return EXIT_USAGE
    except (Failure, extras.MissingExtra) as exc:
        print(f"pointmass: error: {exc}", file=sys.stderr)
        return EXIT_FAILURE
    except Terminated as exc:
        print(f"pointmass: stopped by {exc}", file=sys.stderr)
        return 143
    except KeyboardInterrupt:
        print("pointmass: interrupted", file=sys.stderr)
        return 130
    except Exception as exc:
        status = _interrupted_status()
        if status is not None:  # a signal cut a compile short (``_interrupted_status``)
            print(f"pointmass: interrupted ({type(exc).__name__} after the signal: {exc})",
                  file=sys.stderr)
            return status
        # Matched by name so this module never imports the renderer or the window itself.
        names = {c.__name__ for c in type(exc).__mro__}
        if "NoDisplayError" in names:
            print(f"pointmass: error: {exc}", file=sys.stderr)
            return EXIT_USAGE
        if "RenderUnavailable" in names:
            print(f"pointmass: error: {exc}", file=sys.stderr)
            return EXIT_FAILURE
        raise


if __name__ == "__main__":
    sys.exit(main())
