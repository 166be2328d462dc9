"""Spring-mass simulator for physics teaching: the command line.

    python main.py                        the Simple Example (`vertical`) in the browser
    python main.py SCENE                  a scene in the browser (--no-browser prints its URL, --port P)
    python main.py --list                 the scenes, with their scenarios
    python main.py SCENE --constants      each constant with its value, unit and meaning
    python main.py SCENE --headless       run to the question time and print the final state
        [--set NAME=VALUE ...] [--scenario N] [--preset NAME] [--integrator NAME] [--until T]
        [--json] [--csv FILE]
    python main.py SCENE --steps N        the first N momentum updates as a table to check by hand
    python main.py SCENE --plot FILE.png  a figure of the position and energy graphs (needs matplotlib)
    python main.py SCENE --data FILE      the model against a measured run: offsets, RMS residual
        [--fit k,b] [--data-column NAME] [--run N] [--coordinate x|y|z] [--json] [--plot FILE.png]
    python main.py SCENE --mystery FILE [--seed N]   a measured-looking run with hidden k and b
    python main.py SCENE --show-answer --seed N      the hidden k and b of that mystery file
    python main.py SCENE --data FILE --page         the data on the browser page, with its Fit button

--arrows p,F_net,forces,split (or --no-arrows) chooses the arrows drawn on each mass, in the browser
and in the program --vpython and --webvpython write (default: the scene's VIEW).
--preset NAME applies one of the scene's presets ("Moon gravity", "critical damping", ...; --constants
lists them) in the browser and headless alike, after --scenario and before --set.
--steps and --plot always run headless, so they need no --headless. --json and --csv describe a
headless run and are an error without --headless. Bad input gives one line `error: ...` and exit
status 2; a run that blows up gives its reason (Δt and the stability limit) and exit status 1.
"""
from __future__ import annotations

import argparse
import os
import signal
import sys
import warnings


def _stop_while_loading(signum, frame):
    """Ctrl-C or SIGTERM while numpy and the scenes load: nothing has started, so stop at once."""
    os.write(2, b"stopped: interrupted while loading; nothing was run\n")
    os._exit(128 + signum)


if __name__ == "__main__":  # run() takes over once everything is loaded
    signal.signal(signal.SIGINT, _stop_while_loading)
    signal.signal(signal.SIGTERM, _stop_while_loading)

from export import files  # noqa: E402
from export.arrows import parse_arrows  # noqa: E402
from reports import headless, terminal  # noqa: E402
from physics.integrators import DEFAULT_INTEGRATOR, INTEGRATORS  # noqa: E402
from physics.simulate import BlowUpError  # noqa: E402
from scenes import catalog  # noqa: E402
from scenes import ConstantError, check_value  # noqa: E402
from lab import LabError  # noqa: E402


EXAMPLES = """examples:
  python main.py --list
  python main.py vertical --constants
  python main.py vertical --headless                  the Simple Example: y = -1.73088 m at t = 0.2 s
  python main.py damped --headless --set dt=0.001     the Middling Example with a smaller step
  python main.py driven --headless --scenario 3 --json
  python main.py vertical --headless --preset "Moon gravity"
  python main.py damped --preset "critical damping"    no overshoot, in the browser
  python main.py vertical --steps 2                   the first two updates, to check by hand
  python main.py regimes --plot regimes.png           the page's damping figure
  python main.py damped --data examples/data/vernier.csv --fit k,b --set dt=0.001
                                                      fit k and b to a motion detector's run
  python main.py damped --mystery spring.csv --seed 12   a mystery spring for class
"""


class UsageError(ValueError):
    """Options that do not fit together, or a value out of range: a one-line message."""


class Parser(argparse.ArgumentParser):
    """argparse, but a bad option is one line on stderr (no usage block), with exit status 2."""

    def error(self, message):
        self.exit(2, f"error: {message} (see 'python main.py --help')\n")


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
    parser.add_argument("--headless", action="store_true", help="run without a browser and print the result")
    parser.add_argument("--set", action="append", default=[], metavar="NAME=VALUE", dest="assignments",
                        help="change a constant, e.g. --set k=25 or --set r0=0,-1.2,0 (may repeat)")
    parser.add_argument("--scenario", type=int, metavar="N", help="one of the scene's numbered scenarios")
    parser.add_argument("--preset", metavar="NAME",
                        help="one of the scene's presets, e.g. \"Moon gravity\" or \"critical damping\" "
                             "(a unique beginning is enough; --constants lists them)")
    parser.add_argument("--integrator", choices=list(INTEGRATORS), default=None,
                        help=f"stepping method (default {DEFAULT_INTEGRATOR}, the page's update)")
    parser.add_argument("--until", type=float, metavar="T",
                        help="run until this time, s (default: the scene's question time)")
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
    parser.add_argument("--overwrite", action="store_true",
                        help="let --csv, --plot, --vpython or --webvpython replace an existing Python file "
                             "this program did not write (its own files are never replaced)")
    data = parser.add_argument_group("a real spring (measured data, the fit, a mystery spring)")
    data.add_argument("--data", metavar="FILE",
                      help="compare the model with a measured position against time (Tracker, Vernier, "
                           "PASCO, Logger Pro or --csv file): fits a time and a position offset, prints "
                           "the RMS residual; with --plot, draws both")
    data.add_argument("--fit", metavar="NAMES", help="with --data: also fit these constants, e.g. k,b")
    data.add_argument("--data-column", metavar="NAME",
                      help="with --data: the position column to read (a unique part of its header, or "
                           "its number from 1)")
    data.add_argument("--run", type=int, metavar="N", help="with --data: read run N of several (default 1)")
    data.add_argument("--coordinate", choices=("x", "y", "z"),
                      help="with --data: the model's coordinate to compare (default: the scene's plotted one)")
    data.add_argument("--page", action="store_true",
                      help="with --data: show the data on the browser page instead (dots on its position "
                           "graph, the RMS residual, a Fit button that fits --fit's names, or k,b)")
    data.add_argument("--mystery", metavar="FILE",
                      help="write a measured-looking run of a spring with hidden k and b (Vernier CSV)")
    data.add_argument("--seed", type=int, metavar="N", help="with --mystery or --show-answer: which mystery")
    data.add_argument("--show-answer", action="store_true",
                      help="with --seed N: print the hidden constants of that mystery spring")
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


def list_scenes() -> tuple[str, list[str]]:
    """Each scene with its one-line description, and its numbered scenarios if it has any; and
    what is wrong with each scene file that is not valid Python or was left out (read from the
    files as text: no scene runs)."""
    names = list(catalog.SCENE_NAMES)
    width = max(len(name) for name in names)
    lines, problems = [], list(catalog.SKIPPED.values())
    for name in names:
        try:
            summary, labels = catalog.describe(name)
        except ConstantError as problem:
            problems.append(str(problem))
            continue
        lines.append(f"{name:<{width}}  {summary}")
        for number, label in enumerate(labels, start=1):
            lines.append(f"{'':<{width}}    --scenario {number}: {label}")
    return "\n".join(lines), problems


def presets_report(setup) -> str:
    """The scene's presets with what each changes, for --constants: `critical damping   b = 2√(mk) = 40 kg/s`."""
    from scenes import format_value

    options = catalog.presets(setup)
    if not options:
        return "presets: none for this scene"
    width = max(len(label) for label, _ in options)
    lines = ["presets (--preset NAME):"]
    named = dict(catalog.presets(setup, whole=False))   # a scenario's own changes; it sets its whole case
    for label, overrides in options:
        changes = []
        for name, value in named[label].items():
            unit = setup.constants[name].unit
            if value is None:  # critical damping, from the m and k set now
                value = catalog.resolve({**setup.values, name: None})[name]
                changes.append(f"{name} = 2√(mk) = {format_value(value, unit)}")
            else:
                changes.append(f"{name} = {format_value(value, unit)}")
        rest = "; m, k and the rest of its case from the scene file" if len(overrides) > len(named[label]) else ""
        lines.append(f"  {label:<{width}}   {', '.join(changes)}{rest}")
    return "\n".join(lines)


BROWSER_ONLY = (("--port", "port"), ("--no-browser", "no_browser"), ("--projector", "projector"))
RUN_OPTIONS = (("--headless", "headless"), ("--json", "json"), ("--csv", "csv"), ("--plot", "plot"),
               ("--steps", "steps"), ("--until", "until"), ("--integrator", "integrator"))
PROGRAM_OPTIONS = (("--vpython", "vpython"), ("--webvpython", "webvpython"))
OUTPUT_FILES = (("--csv", "csv"), ("--plot", "plot"), *PROGRAM_OPTIONS)


def headless_run(args) -> bool:
    """Whether the command runs without the browser: --headless, and --steps and --plot, which imply it
    (and --data, --mystery and --show-answer, which never open the page)."""
    return (args.headless or args.steps is not None or args.plot is not None
            or (lab_command(args) is not None and not args.page))


LAB_OPTIONS = (("--fit", "fit"), ("--data-column", "data_column"), ("--run", "run"),
               ("--coordinate", "coordinate"), ("--seed", "seed"), ("--page", "page"))


def lab_command(args) -> str | None:
    """Which of --data, --mystery and --show-answer was given (None: none of them)."""
    given = [flag for flag, attribute in (("--data", "data"), ("--mystery", "mystery"),
                                          ("--show-answer", "show_answer")) if _given(args, attribute)]
    return given[0] if given else None


def check_lab_options(args) -> None:
    """--data, --mystery and --show-answer: one at a time, with only the flags that do something."""
    commands = [flag for flag, attribute in (("--data", "data"), ("--mystery", "mystery"),
                                             ("--show-answer", "show_answer")) if _given(args, attribute)]
    if len(commands) > 1:
        raise UsageError(f"{commands[0]} and {commands[1]} are separate jobs; give one of them")
    command = commands[0] if commands else None
    for flag, attribute in (("--list", "list"), ("--constants", "constants")):
        if command and _given(args, attribute):
            raise UsageError(f"{flag} only lists, so {command} would do nothing; leave out one of them")
    allowed = {"--data": {"fit", "data_column", "run", "coordinate", "page"},
               "--mystery": {"seed", "coordinate"}, "--show-answer": {"seed", "coordinate"}}.get(command, set())
    for flag, attribute in LAB_OPTIONS:
        if _given(args, attribute) and attribute not in allowed:
            needs = "--data" if attribute != "seed" else "--mystery or --show-answer"
            raise UsageError(f"{flag} needs {needs}" + (f" (it does nothing with {command})" if command else ""))
    if command is None:
        return
    if command == "--show-answer" and args.seed is None:
        raise UsageError("--show-answer needs --seed N, the seed the mystery file was written with")
    if args.run is not None and args.run < 1:
        raise UsageError(f"--run needs a whole number of 1 or more (got {args.run})")
    others = [(flag, attribute) for flag, attribute in (("--csv", "csv"), ("--steps", "steps"),
                                                        ("--until", "until"), *PROGRAM_OPTIONS)]
    others += [("--json", "json"), ("--plot", "plot"), ("--headless", "headless")] if args.page else BROWSER_ONLY
    if command != "--data":
        others += [("--json", "json"), ("--plot", "plot"), ("--integrator", "integrator")]
    for flag, attribute in others:
        if _given(args, attribute):
            page = (" (add --page to show the data on the page)" if command == "--data" and
                    (flag, attribute) in BROWSER_ONLY else "")
            raise UsageError(f"{flag} does nothing with {command}{' --page' if args.page else ''}; "
                             f"leave out one of them{page}")


def _given(args, attribute) -> bool:
    value = getattr(args, attribute)
    return value is not None and value is not False and value != []  # --port 0 is given


def check_options(args) -> None:
    """Combinations and ranges argparse cannot check by itself: each flag must do something."""
    check_lab_options(args)
    runs_headless = headless_run(args)
    if args.list:
        others = [flag for flag, attribute in (("--constants", "constants"), ("--set", "assignments"),
                                               ("--scenario", "scenario"), ("--preset", "preset"),
                                               *RUN_OPTIONS, *PROGRAM_OPTIONS, *BROWSER_ONLY,
                                               ("--overwrite", "overwrite"))
                  if _given(args, attribute)]
        if args.scene is not None or others:
            what = f"scene {args.scene!r}" if args.scene is not None else others[0]
            raise UsageError(f"--list takes no scene or other option (got {what}); "
                             f"use 'python main.py SCENE --constants' for one scene")
        return
    if args.constants:
        for flag, attribute in (*RUN_OPTIONS, *PROGRAM_OPTIONS, *BROWSER_ONLY):
            if _given(args, attribute):
                raise UsageError(f"--constants only prints the constants, so {flag} would do nothing; "
                                 f"leave out one of them")
    if lab_command(args) is not None:
        return
    for flag, given in (("--json", args.json), ("--csv", args.csv is not None)):
        if given and not args.headless:
            raise UsageError(f"{flag} needs --headless (it describes a run without the browser)")
    if runs_headless:
        for flag, attribute in BROWSER_ONLY:
            if _given(args, attribute):
                raise UsageError(f"{flag} is for the browser page, and a headless run (--headless, "
                                 f"--steps, --plot) has none; leave out one of them")
    programs = [flag for flag, attribute in PROGRAM_OPTIONS if _given(args, attribute)]
    if programs and not runs_headless:
        for flag, attribute in BROWSER_ONLY:
            if _given(args, attribute):
                raise UsageError(f"{flag} is for the browser page, and {programs[0]} only writes a "
                                 f"program (no page opens); leave out one of them")
    if args.until is not None:
        if not runs_headless and not programs:
            raise UsageError("--until needs --headless, or --vpython or --webvpython (the program runs that "
                             "long); the browser runs until you stop it")
        try:
            check_value("until", args.until, "s")  # the same range as the scenes' own `until`
        except ConstantError as problem:
            raise UsageError(f"--{problem}") from None
        if args.steps is not None and args.csv is None and args.plot is None:
            raise UsageError("--until does nothing with --steps alone (the table stops after N steps); "
                             "leave out one of them")
    if args.arrows is not None:
        try:
            args.arrows = parse_arrows(args.arrows)
        except ValueError as problem:
            raise UsageError(str(problem)) from None
        if runs_headless and not programs:
            raise UsageError("--arrows (and --no-arrows) is for the page and the program (--vpython, --webvpython), and a "
                             "headless run draws none; leave it out")
    if args.steps is not None and args.steps < 1:
        raise UsageError(f"--steps needs a whole number of 1 or more (got {args.steps})")
    if args.port is not None and not 1 <= args.port <= 65535:
        raise UsageError(f"--port must be a whole number from 1 to 65535 (got {args.port}); "
                         f"leave --port out for any free port")
    outputs = [(flag, getattr(args, attribute)) for flag, attribute in OUTPUT_FILES
               if getattr(args, attribute) not in (None, files.STDOUT)]
    if args.overwrite and not outputs:
        raise UsageError("--overwrite does nothing without a file to write (--csv, --plot, --vpython or "
                         "--webvpython); leave it out")
    for n, (flag, path) in enumerate(outputs):
        for other, other_path in outputs[n + 1:]:
            if files.same_file(path, other_path):
                raise UsageError(f"{flag} and {other} both write {path!r}: give them different files")
    printers = [f"{flag} -" for flag, attribute in PROGRAM_OPTIONS if getattr(args, attribute) == files.STDOUT]
    if runs_headless:
        printers.append("--json" if args.json else "--steps" if args.steps is not None else
                        "--headless (its report)")
    if len(printers) > 1:
        raise UsageError(f"{printers[0]} and {printers[1]} would both print on standard output, one "
                         f"after the other; write the program to a file instead")


def build_model(args, setup):
    """The scene's model, from its constants; UsageError if the physics cannot take them, or if
    --integrator would do nothing (a scene that steps each mass with its own method)."""
    try:
        model = setup.build()
    except ValueError as problem:  # a combination of constants the physics cannot take
        raise UsageError(str(problem)) from None
    if args.integrator is not None and model.integrators is not None:
        raise UsageError(f"scene {setup.name!r} steps its masses with {', '.join(model.integrators)}, "
                         f"one each, so --integrator {args.integrator} would do nothing; leave it out")
    return model


def run_headless(args, setup, model) -> int:
    """The headless paths: the step table, the final state (text or JSON), the CSV file and the figure.

    Output files are checked before anything runs, so a typo in a path costs no computing time.
    """
    until = model.until if args.until is None else args.until
    every_step = args.csv is not None or args.plot is not None
    engine = model.simulation(args.integrator)   # the one that runs: its cost is measured once
    if args.steps is None or every_step:  # a run too long is refused before anything prints
        headless.step_count(engine, until=until, rows_per_step=model.state.count if every_step else 0,
                            shortest=headless.shortest_until(setup))
    if args.csv is not None:
        files.check_writable(args.csv, what="CSV file", overwrite=args.overwrite)
    if args.plot is not None:
        files.check_writable(args.plot, what="figure", overwrite=args.overwrite)
        from reports import plotting

        plotting.check_format(args.plot)
    warning = headless.stability_warning(model, model.methods(args.integrator))
    if warning:
        print(warning, file=sys.stderr)

    if args.steps is not None:
        table = headless.step_table(setup, model=model, integrator=args.integrator, steps=args.steps)
        if args.json:
            rows = table.pop("rows")
            print(headless.to_json(headless.with_warning({**table, "steps": args.steps, "step_table": rows}, warning)))
        else:
            print(headless.format_step_table(table))
        if args.csv is None and args.plot is None:
            return 0

    result = headless.simulate(setup, model=model, integrator=args.integrator, until=until,
                               every_step=every_step, engine=engine)
    note = headless.stop_note(model, until=until)
    if note:
        print(note, file=sys.stderr)
    if args.csv is not None:
        headless.write_csv(result, args.csv)
    if args.plot is not None:
        from reports import plotting

        plotting.plot(result, args.plot)
    if args.steps is None:
        print(headless.to_json(headless.with_warning(headless.as_json(result), warning)) if args.json
              else headless.final_report(result))
    return 0


def write_programs(args, setup, model, *, warn: bool) -> None:
    """--vpython FILE.py and --webvpython FILE.py: the scene as a program to hand out (export/).

    Every program is made and every path checked before any file is written, so bad input leaves
    no file at all. With `warn`, a Δt the program's motion will grow or blow up at is said on
    stderr (the program is still written: showing that may be the lesson).
    """
    import export

    if args.until is not None:   # the program runs that long (the scene's `until` constant)
        setup = setup.with_values(until=float(args.until))
    if warn:
        try:
            warning = headless.stability_warning(model, model.methods(args.integrator))
        except BlowUpError as problem:
            warning = f"warning: {problem}; the program is written as asked"
        if warning:
            print(warning, file=sys.stderr)

    try:
        texts = [(path, export.program(setup, integrator=args.integrator, web=web, arrows=args.arrows))
                 for path, web in ((args.vpython, False), (args.webvpython, True)) if path is not None]
        for path, _ in texts:
            if path != "-":
                export.check_path(path, overwrite=args.overwrite)
        if args.vpython not in (None, "-") and os.path.basename(args.vpython).lower() in ("vpython.py", "vpython.pyw"):
            raise UsageError(f"a program called {os.path.basename(args.vpython)} cannot run: its "
                             f"`from vpython import *` would import the program itself instead of the vpython "
                             f"library; give it another name, like spring.py")
        for path, text in texts:
            if path == "-":
                print(text, end="")
            else:
                export.write_program(path, text, overwrite=args.overwrite)
                print(f"wrote {path}", file=sys.stderr)
    except ValueError as problem:   # export.ProgramError, or constants the physics cannot take
        raise UsageError(str(problem)) from None


def main(argv=None) -> int:
    args = build_parser().parse_args(argv)
    try:
        check_options(args)
        if args.list:
            listing, problems = list_scenes()
            print(listing)
            for problem in problems:  # the other scenes are listed, and run, as usual
                print(f"error: {problem}", file=sys.stderr)
            return 2 if problems else 0
        setup = catalog.configure(catalog.DEFAULT_SCENE if args.scene is None else args.scene,
                                  assignments=args.assignments,
                                  scenario=args.scenario, preset=args.preset)
        if args.constants:
            print(headless.constants_report(setup))
            print(presets_report(setup))
            return 0
        model = build_model(args, setup)
        if args.page:
            data = page_data(args, setup)
        elif lab_command(args) is not None:
            from reports import measured

            run_lab = {"--data": measured.run_data, "--mystery": measured.run_mystery,
                       "--show-answer": measured.show_answer}[lab_command(args)]
            return run_lab(args, setup)
        runs_headless = headless_run(args)
        if args.vpython is not None or args.webvpython is not None:
            write_programs(args, setup, model, warn=not runs_headless)   # then a headless run too, if asked
            if not runs_headless:
                return 0
        if runs_headless:
            return run_headless(args, setup, model)
    except (ConstantError, UsageError, files.OutputError, LabError) as problem:
        print(f"error: {problem}", file=sys.stderr)
        return 2
    except BlowUpError as problem:
        print(f"error: {problem}", file=sys.stderr)
        return 1
    from browser.clock import check_live_cost
    from browser.view import show

    try:
        check_live_cost(model, args.integrator)
    except ValueError as problem:
        print(f"error: {problem}", file=sys.stderr)
        return 2
    # the page's integrator menu starts where a headless run would: the scene's own default (rk4 for
    # resonance), else the page's euler-cromer
    integrator = model.methods(args.integrator)[0]

    preset = catalog.find_preset(setup, args.preset)[0] if args.preset else None
    if preset is None and args.scenario is not None:  # the page's preset menu names the scenario shown
        preset = next((label for label, _ in catalog.presets(setup)
                       if label.startswith(f"scenario {args.scenario}:")), None)
    sys.exit(show(setup, model, integrator=integrator, port=args.port,
                  open_browser=not args.no_browser, preset=preset, projector=args.projector,
                  arrows=args.arrows, data=data if args.page else None))


def page_data(args, setup):
    """--data FILE --page: the file read (a bad one is one line before any page opens) and the
    names the page's Fit button fits (--fit, checked now), for browser/data_panel.py."""
    from browser.data_panel import MeasuredData
    from lab import compare, readers

    coordinate = compare.coordinate_of(setup, args.coordinate)
    measured = readers.read(args.data, column=args.data_column, run=args.run, coordinate=coordinate)
    names = compare.check_names(setup, args.fit.split(",")) if args.fit else ()
    return MeasuredData(measured=measured, fit_names=names, coordinate=args.coordinate)


class Terminated(BaseException):
    """SIGTERM arrived: unwinds like Ctrl-C, so every half-written output file is removed on the way."""


def _terminate(signum, frame):
    raise Terminated()


def _one_line_warning(message, category, filename, lineno, file=None, line=None):
    """A warning from the physics (a force the fast loop cannot trace) as one line on stderr."""
    print(f"warning: {' '.join(str(message).split())}", file=file or sys.stderr)


def run(argv=None) -> int:
    """main() as a user meets it: whatever happens, at most one line on stderr and never a traceback.

    Ctrl-C exits with status 130 and SIGTERM with 143 (128 + the signal's number, as a shell
    reports them); an output file being written is removed, the old one left as it was. Anything
    unforeseen is a bug of ours: one line naming it, and exit status 1.
    """
    terminal.install()   # a symbol the terminal cannot write (Δt, ω, ²) is spelled in ASCII (dt, omega, ^2)
    previous = signal.signal(signal.SIGINT, signal.default_int_handler), signal.signal(signal.SIGTERM, _terminate)
    shown, warnings.showwarning = warnings.showwarning, _one_line_warning
    stdout, sys.stdout = sys.stdout, terminal.GuardedOutput(sys.stdout)  # closed or full: one line
    try:
        status = main(argv)
        sys.stdout.flush()   # a full disk shows here, while there is still a status to give
        return status
    except terminal.OutputStreamError as problem:
        terminal.discard_output(stdout)
        print(f"error: {problem}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("stopped: interrupted (Ctrl-C); no file was left half-written", file=sys.stderr)
        return 128 + signal.SIGINT
    except Terminated:
        print("stopped: terminated (SIGTERM); no file was left half-written", file=sys.stderr)
        return 128 + signal.SIGTERM
    except BrokenPipeError:  # output piped into `head` and cut short: not an error of ours
        terminal.discard_output(stdout)
        return 0
    except MemoryError:
        print("error: not enough memory for this run; use a larger dt or a shorter --until", file=sys.stderr)
        return 1
    except Exception as problem:  # the last resort: a bug, but still no traceback for the user
        text = " ".join(str(problem).split()) or "no message"
        print(f"error: unexpected {type(problem).__name__}: {text} (a bug in main.py; please report "
              f"it with the command you ran)", file=sys.stderr)
        return 1
    finally:
        sys.stdout = stdout
        signal.signal(signal.SIGINT, previous[0])
        signal.signal(signal.SIGTERM, previous[1])
        warnings.showwarning = shown


if __name__ == "__main__":
    sys.exit(run())
