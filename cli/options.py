"""The command line's options: what each flag is (argparse) and which flags go together.

Every flag must do something: a combination where one would be ignored (--json without
--headless, --port with a headless run, two outputs on standard output, two flags writing one
file) is a UsageError, one line naming both flags, before anything runs. main.py reads the
options here, then hands over to reports/, export/ or browser/.
"""
from __future__ import annotations

import argparse

from export import files
from export.arrows import parse_arrows
from export.lines import one_line  # noqa: F401  (main.py and the parser write every message through it)
from physics.integrators import DEFAULT_INTEGRATOR, INTEGRATORS
from scenes import ConstantError, catalog, check_value


EXAMPLES = """examples:
  python main.py --list
  python main.py vertical --constants
  python main.py vertical --forces                    the forces it takes, on or off, with their constants
  python main.py vertical --headless                  the Simple Example: y = -1.73088 m at t = 0.2 s
  python main.py damped --headless --set dt=0.001     the Middling Example with a smaller step
  python main.py driven --headless --scenario 3 --json
  python main.py vertical --headless --preset "Moon gravity"
  python main.py damped --preset "critical damping"    no overshoot, in the browser
  python main.py vertical --steps 2                   the first two updates, to check by hand
  python main.py vertical --headless --force "push=vector(0, 50, 0)"   a 50 N push up: as g = 4.8
  python main.py regimes --plot out/regimes.png       the page's damping figure
  python main.py damped --data examples/data/vernier.csv --fit k,b --set m=0.5
                                                      fit k and b to a motion detector's run
  python main.py damped --mystery out/spring.csv --seed 12   a mystery spring for class

exit status: 0 done; 2 bad input (one line says what); 1 a run that blew up, or a bug of ours;
3 a fit whose numbers cannot be trusted (--data --fit): its first line says why, the figures follow
"""


class UsageError(ValueError):
    """Options that do not fit together, or a value out of range: a one-line message."""


# What str.splitlines() breaks a line at, and the other control characters a terminal acts on.
class Parser(argparse.ArgumentParser):
    """argparse, but a bad option is one line on stderr (no usage block), with exit status 2."""

    def error(self, message):
        self.exit(2, f"error: {one_line(message)} (see 'python main.py --help')\n")


def build_parser() -> argparse.ArgumentParser:
    parser = Parser(prog="main.py", formatter_class=argparse.RawDescriptionHelpFormatter,
                    description="Iterative prediction of spring-mass systems: the momentum update\n"
                    "p_f = p_i + F_net Δt, v_f = p_f / m, r_f = r_i + v_f Δt.",
                    epilog=EXAMPLES)
    parser.add_argument("scene", nargs="?", default=None,
                        help=f"scene name (default {catalog.DEFAULT_SCENE}; see --list)")
    parser.add_argument("--list", action="store_true", help="list the scenes and their scenarios")
    parser.add_argument("--constants", action="store_true",
                        help="print each constant with its value, unit and meaning")
    parser.add_argument("--forces", action="store_true",
                        help="list every force the scene accepts, on or off: its law, its constants "
                             "(the names --set takes) and which a slider moves")
    parser.add_argument("--headless", action="store_true", help="run without a browser and print the result")
    parser.add_argument("--set", action="append", default=[], metavar="NAME=VALUE", dest="assignments",
                        help="change a constant, e.g. --set k=25 or --set r0=0,-1.2,0 (may repeat)")
    parser.add_argument("--force", action="append", default=[], metavar="NAME=EXPRESSION", dest="added_forces",
                        help="add a force written in the program's names, e.g. --force \"push=vector(2, 0, 0)\" or "
                             "--force \"wind=-0.5*mag(v)*v\" (r, v, p, t, m, k, b, g, dt; vector, mag, hat, dot, "
                             "cross, cos, sin, exp, sqrt, pi; may repeat): its arrow, the run, the program")
    parser.add_argument("--scenario", type=int, metavar="N", help="one of the scene's numbered scenarios")
    parser.add_argument("--preset", metavar="NAME",
                        help="one of the scene's presets, e.g. \"Moon gravity\" or \"critical damping\" "
                             "(a unique beginning is enough; --constants lists them)")
    parser.add_argument("--integrator", choices=list(INTEGRATORS), default=None,
                        help=f"stepping method (default {DEFAULT_INTEGRATOR}, the page's update)")
    parser.add_argument("--until", type=float, metavar="T",
                        help="run until this time, s (default: the scene's question time; a handed-out "
                             "program runs as long as the page's graph shows and prints its answer at the "
                             "question time)")
    parser.add_argument("--json", action="store_true", help="with --headless: print one JSON object")
    parser.add_argument("--csv", metavar="FILE", help="with --headless: write every step to a CSV file")
    parser.add_argument("--steps", type=int, metavar="N",
                        help="print the first N steps as a table (t, F_net, p_f, v_f, r_f); implies --headless")
    parser.add_argument("--plot", metavar="FILE.png",
                        help="save the position and energy graphs as a figure; implies --headless")
    parser.add_argument("--vpython", metavar="FILE.py",
                        help="write the scene as a standalone VPython program to hand out ('-': print it)")
    parser.add_argument("--webvpython", metavar="FILE.py",
                        help="the same program for Web VPython (glowscript.org, trinket)")
    parser.add_argument("--html", metavar="FILE.html",
                        help="the scene as one HTML file that runs offline in any browser (GlowScript inside: "
                             "no install, no network), with the page's controls")
    parser.add_argument("--overwrite", action="store_true",
                        help="let --csv, --plot, --vpython, --webvpython or --mystery replace an existing "
                             "file this program did not write (its own outputs are replaced without it; "
                             "the program's own files and the --data file never are)")
    _add_lab_options(parser)
    parser.add_argument("--arrows", metavar="LIST",
                        help="arrows on each mass, in the page and the program: any of p,F_net,forces,split "
                             "(default: the scene's own; vertical, damped, driven and pendulum show p,F_net)")
    parser.add_argument("--no-arrows", action="store_const", const="", dest="arrows",
                        help="no arrows (the same as --arrows '')")
    parser.add_argument("--no-browser", action="store_true",
                        help="print the page's URL instead of opening a browser")
    parser.add_argument("--port", type=int, metavar="P", help="port for the browser page")
    parser.add_argument("--projector", action="store_true",
                        help="open the page in projector mode: text of 22 px or more, thicker lines")
    return parser


def _add_lab_options(parser: argparse.ArgumentParser) -> None:
    """--data, --fit, --mystery and the rest: a real spring (lab/)."""
    data = parser.add_argument_group("a real spring (measured data, the fit, a mystery spring)")
    data.add_argument("--data", metavar="FILE",
                      help="compare the model with a measured position against time (Tracker, Vernier, "
                           "PASCO, Logger Pro or --csv file): fits a time and a position offset, prints "
                           "the RMS residual; with --plot, draws both")
    data.add_argument("--fit", metavar="NAMES",
                      help="with --data: also fit these constants, e.g. k,b (and where the mass was let go, "
                           "r0, unless --set r0 gives it); the fit chooses the model's integrator and dt "
                           "unless --integrator or --set dt does; exit status 3 if its numbers cannot be "
                           "trusted")
    data.add_argument("--data-column", metavar="NAME",
                      help="with --data: the position column to read (a unique part of its header, or "
                           "its number from 1)")
    data.add_argument("--run", type=int, metavar="N", help="with --data: read run N of several (default 1)")
    data.add_argument("--coordinate", choices=("x", "y", "z"),
                      help="with --data: the model's coordinate to compare (default: the scene's plotted one)")
    data.add_argument("--data-sign", type=int, choices=(1, -1), metavar="1|-1",
                      help="with --data: -1 where the data's axis points the other way from the model's (a "
                           "detector above the mass, a video's y axis down), 1 where it points the same way "
                           "(default: both are tried and the better match is kept)")
    data.add_argument("--page", action="store_true",
                      help="with --data: show the data on the browser page instead (dots on its position "
                           "graph, the RMS residual, a Fit button that fits --fit's names, or k,b)")
    data.add_argument("--mystery", metavar="FILE",
                      help="write a measured-looking run of a spring with hidden k and b (Vernier CSV)")
    data.add_argument("--seed", type=int, metavar="N", help="with --mystery or --show-answer: which mystery")
    data.add_argument("--show-answer", action="store_true",
                      help="with --seed N: print the hidden constants of that mystery spring")


BROWSER_ONLY = (("--port", "port"), ("--no-browser", "no_browser"), ("--projector", "projector"))
RUN_OPTIONS = (("--headless", "headless"), ("--json", "json"), ("--csv", "csv"), ("--plot", "plot"),
               ("--steps", "steps"), ("--until", "until"), ("--integrator", "integrator"))
PROGRAM_OPTIONS = (("--vpython", "vpython"), ("--webvpython", "webvpython"), ("--html", "html"))
OUTPUT_FILES = (("--csv", "csv"), ("--plot", "plot"), *PROGRAM_OPTIONS)


def headless_run(args) -> bool:
    """Whether the command runs without the browser: --headless, and --steps and --plot, which imply it
    (and --data, --mystery and --show-answer, which never open the page)."""
    return (args.headless or args.steps is not None or args.plot is not None
            or (lab_command(args) is not None and not args.page))


LAB_OPTIONS = (("--fit", "fit"), ("--data-column", "data_column"), ("--run", "run"),
               ("--coordinate", "coordinate"), ("--data-sign", "data_sign"), ("--seed", "seed"), ("--page", "page"))


LAB_COMMANDS = (("--data", "data"), ("--mystery", "mystery"), ("--show-answer", "show_answer"))


def _lab_commands(args) -> list[str]:
    """The ones of --data, --mystery and --show-answer given."""
    return [flag for flag, attribute in LAB_COMMANDS if _given(args, attribute)]


def lab_command(args) -> str | None:
    """Which of --data, --mystery and --show-answer was given (None: none of them)."""
    given = _lab_commands(args)
    return given[0] if given else None


def check_lab_options(args) -> None:
    """--data, --mystery and --show-answer: one at a time, with only the flags that do something."""
    commands = _lab_commands(args)
    if len(commands) > 1:
        raise UsageError(f"{commands[0]} and {commands[1]} are separate jobs; give one of them")
    command = commands[0] if commands else None
    for flag, attribute in (("--list", "list"), ("--constants", "constants"), ("--forces", "forces")):
        if command and _given(args, attribute):
            raise UsageError(f"{flag} only lists, so {command} would do nothing; leave out one of them")
    if command and _given(args, "added_forces"):
        raise UsageError(f"--force adds a force to a run, the page or a program, and {command} uses the scene's "
                         f"own forces; leave out one of them")
    allowed = {"--data": {"fit", "data_column", "run", "coordinate", "data_sign", "page"},
               "--mystery": {"seed", "coordinate"}, "--show-answer": {"seed", "coordinate"}}.get(command, set())
    for flag, attribute in LAB_OPTIONS:
        if _given(args, attribute) and attribute not in allowed:
            needs = "--data" if attribute != "seed" else "--mystery or --show-answer"
            raise UsageError(f"{flag} needs {needs}" + (f" (it does nothing with {command})" if command else ""))
    if command is None:
        return
    if command == "--show-answer" and args.seed is None:
        raise UsageError("--show-answer needs --seed N, the seed the mystery file was written with")
    if args.seed is not None and args.seed < 0:
        raise UsageError(f"--seed needs a whole number of 0 or more (got {args.seed})")
    if args.run is not None and args.run < 1:
        raise UsageError(f"--run needs a whole number of 1 or more (got {args.run})")
    if args.data_column is not None and not args.data_column.strip():
        raise UsageError("--data-column needs a column: a unique part of its header, or its number from 1 "
                         "(got nothing); leave it out to read the file's position column")
    if args.fit is not None and not args.fit.strip():
        raise UsageError("--fit needs the names of the constants to fit, like --fit k,b (got nothing); "
                         "leave it out to fit only the offsets")
    others = [(flag, attribute) for flag, attribute in (("--csv", "csv"), ("--steps", "steps"),
                                                        ("--until", "until"), *PROGRAM_OPTIONS)]
    others += [("--json", "json"), ("--plot", "plot"), ("--headless", "headless")] if args.page else BROWSER_ONLY
    if command != "--data":
        others += [("--json", "json"), ("--plot", "plot"), ("--integrator", "integrator")]
    if not args.page:   # arrows are drawn on the page only
        others += [(_arrows_flag(args), "arrows")]
    if not (command == "--mystery" or (command == "--data" and args.plot is not None)):
        others += [("--overwrite", "overwrite")]   # it lets --plot or the mystery file replace a file
    for flag, attribute in others:
        if _given(args, attribute):
            page = (" (add --page to show the data on the page)" if command == "--data" and
                    (flag, attribute) in BROWSER_ONLY + ((_arrows_flag(args), "arrows"),) else "")
            raise UsageError(f"{flag} does nothing with {command}{' --page' if args.page else ''}; "
                             f"leave out one of them{page}")
    if command == "--data" and args.plot is not None and files.same_file(args.plot, args.data):
        raise UsageError(f"--plot {args.plot!r} is the --data file (the same file{_how_same(args.plot, args.data)}), "
                         f"and the data is never written over; give the figure another name")


def _arrows_flag(args) -> str:
    """How the user asked for arrows: --no-arrows sets them to ''."""
    return "--no-arrows" if args.arrows == "" else "--arrows"


def _how_same(first: str, second: str) -> str:
    """' under another name' when two paths that name one file are spelt differently."""
    return "" if first == second else ", under another name"


def _given(args, attribute) -> bool:
    value = getattr(args, attribute)
    return value is not None and value is not False and value != []  # --port 0 is given


def check_options(args) -> None:
    """Combinations and ranges argparse cannot check by itself: each flag must do something.

    --arrows is parsed here: args.arrows becomes the tuple of arrows asked for.
    """
    check_lab_options(args)
    if args.list:
        _check_list(args)
        return
    listing = "--constants" if args.constants else "--forces" if args.forces else None
    if listing:
        for flag, attribute in (*RUN_OPTIONS, *PROGRAM_OPTIONS, *BROWSER_ONLY, (_arrows_flag(args), "arrows"),
                                ("--overwrite", "overwrite"), ("--force", "added_forces")):
            if _given(args, attribute):
                raise UsageError(f"{listing} only prints the {listing[2:]}, so {flag} would do nothing; "
                                 f"leave out one of them")
    if lab_command(args) is not None:
        _parse_arrows(args)   # --data --page: the page draws them
        return
    _check_run(args)
    _check_until(args)
    _check_arrows(args)
    if args.steps is not None and args.steps < 1:
        raise UsageError(f"--steps needs a whole number of 1 or more (got {args.steps})")
    if args.port is not None and not 1 <= args.port <= 65535:
        raise UsageError(f"--port must be a whole number from 1 to 65535 (got {args.port}); "
                         f"leave --port out for any free port")
    _check_outputs(args)


def _programs(args) -> list[str]:
    """The program flags given (--vpython, --webvpython)."""
    return [flag for flag, attribute in PROGRAM_OPTIONS if _given(args, attribute)]


def _check_list(args) -> None:
    """--list takes nothing else."""
    others = [flag for flag, attribute in (("--constants", "constants"), ("--forces", "forces"), ("--set", "assignments"),
                                           ("--force", "added_forces"),
                                           ("--scenario", "scenario"), ("--preset", "preset"),
                                           *RUN_OPTIONS, *PROGRAM_OPTIONS, *BROWSER_ONLY,
                                           ("--overwrite", "overwrite"), (_arrows_flag(args), "arrows"))
              if _given(args, attribute)]
    if args.scene is not None or others:
        what = f"scene {args.scene!r}" if args.scene is not None else others[0]
        raise UsageError(f"--list takes no scene or other option (got {what}); "
                         f"use 'python main.py SCENE --constants' for one scene")


def _check_run(args) -> None:
    """--json and --csv need --headless; the browser's flags need the browser."""
    for flag, given in (("--json", args.json), ("--csv", args.csv is not None)):
        if given and not args.headless:
            raise UsageError(f"{flag} needs --headless (it describes a run without the browser)")
    if headless_run(args):
        for flag, attribute in BROWSER_ONLY:
            if _given(args, attribute):
                raise UsageError(f"{flag} is for the browser page, and a headless run (--headless, "
                                 f"--steps, --plot) has none; leave out one of them")
    programs = _programs(args)
    if programs and not headless_run(args):
        for flag, attribute in BROWSER_ONLY:
            if _given(args, attribute):
                raise UsageError(f"{flag} is for the browser page, and {programs[0]} only writes a "
                                 f"program (no page opens); leave out one of them")


def _check_until(args) -> None:
    """--until: only where a run ends, in the range of the scenes' own `until`."""
    if args.until is None:
        return
    if not headless_run(args) and not _programs(args):
        raise UsageError("--until needs --headless, or --vpython or --webvpython or --html (the program runs "
                         "that long); the browser runs until you stop it")
    try:
        check_value("until", args.until, "s")  # the same range as the scenes' own `until`
    except ConstantError as problem:
        raise UsageError(f"--{problem}") from None
    if args.steps is not None and args.csv is None and args.plot is None:
        raise UsageError("--until does nothing with --steps alone (the table stops after N steps); "
                         "leave out one of them")


def _check_arrows(args) -> None:
    """--arrows LIST (or --no-arrows): parsed, and only where arrows are drawn."""
    if args.arrows is None:
        return
    _parse_arrows(args)
    if headless_run(args) and not _programs(args):
        raise UsageError("--arrows (and --no-arrows) is for the page and the program (--vpython, --webvpython, --html), and a "
                         "headless run draws none; leave it out")


def _parse_arrows(args) -> None:
    """args.arrows, the text of --arrows, becomes the tuple of arrow names (UsageError naming an
    unknown one); None stays None (the scene's own)."""
    if isinstance(args.arrows, str):
        try:
            args.arrows = parse_arrows(args.arrows)
        except ValueError as problem:
            raise UsageError(str(problem)) from None


def _check_outputs(args) -> None:
    """--overwrite needs a file; no two flags write one file; at most one prints on standard output."""
    outputs = [(flag, getattr(args, attribute)) for flag, attribute in OUTPUT_FILES
               if getattr(args, attribute) not in (None, files.STDOUT)]
    if args.overwrite and not outputs:
        raise UsageError("--overwrite does nothing without a file to write (--csv, --plot, --vpython, "
                         "--webvpython or --html); leave it out")
    for n, (flag, path) in enumerate(outputs):
        for other, other_path in outputs[n + 1:]:
            if files.same_file(path, other_path):
                raise UsageError(f"{flag} and {other} both write {path!r}: give them different files")
    printers = [f"{flag} -" for flag, attribute in PROGRAM_OPTIONS if getattr(args, attribute) == files.STDOUT]
    if headless_run(args):
        printers.append("--json" if args.json else "--steps" if args.steps is not None else
                        "--headless (its report)")
    if len(printers) > 1:
        raise UsageError(f"{printers[0]} and {printers[1]} would both print on standard output, one "
                         f"after the other; write the program to a file instead")
