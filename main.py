"""Spring-mass simulator for physics teaching: the command line.

    python main.py                        the Simple Example (`vertical`) in the browser
    python main.py SCENE                  a scene in the browser (--no-browser prints its URL, --port P)
    python main.py --list                 the scenes, with their scenarios
    python main.py SCENE --constants      each constant with its value, unit and meaning
    python main.py SCENE --forces         every force the scene takes, on or off, with its constants
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
status 2; a run that blows up gives its reason (Δt and the stability limit) and exit status 1; a fit
(--data --fit) whose numbers cannot be trusted prints why on its first line, then the figures, and
exits with status 3.
"""
from __future__ import annotations

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
    # numpy asks Linux for huge pages for every array of 4 MB or more (a documented switch, read
    # when numpy is imported). Where the kernel then compacts memory to find them (transparent
    # hugepages "madvise", Ubuntu's default), the first touch of a big recording costs more than
    # the huge pages ever save here: each big array is written once and read once. Measured on
    # `resonance --set count=10000` (its 304 MB measuring window): 0.60-0.68 s of system time with
    # them, 0.19-0.29 s without, the same user time. A value the user set is kept.
    os.environ.setdefault("NUMPY_MADVISE_HUGEPAGE", "0")

from cli.options import UsageError, build_parser, check_options, headless_run, lab_command, one_line  # noqa: E402
from export import files  # noqa: E402
from reports import csv_file, headless, json_report, step_table, terminal, text  # noqa: E402
from physics.forces import DeclarationError  # noqa: E402
from physics.simulate import BlowUpError  # noqa: E402
from scenes import catalog  # noqa: E402
from scenes import ConstantError  # noqa: E402
from lab import LabError  # noqa: E402


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

    The run's cost is checked (once: simulate is handed the plan) and output files are checked before
    anything runs, so a typo in a path costs no computing time.
    """
    until = model.until if args.until is None else args.until
    every_step = args.csv is not None or args.plot is not None
    run = None
    if args.steps is None or every_step:  # a run too long is refused before anything prints
        run = headless.plan(setup, model=model, integrator=args.integrator, until=until, every_step=every_step)
    if args.csv is not None:
        files.check_writable(args.csv, what="CSV file", overwrite=args.overwrite)
    if args.plot is not None:
        files.check_writable(args.plot, what="figure", overwrite=args.overwrite)
        from reports import plotting

        plotting.check_format(args.plot)
    warning = headless.stability_warning(model, model.methods(args.integrator))
    if warning:
        print(one_line(warning), file=sys.stderr)
    if args.steps is not None:
        print_step_table(args, setup, model, warning)
        if run is None:
            return 0
    result = headless.simulate(setup, checked=run)
    note = headless.stop_note(model, until=until)
    if note:
        print(one_line(note), file=sys.stderr)
    if args.csv is not None:
        csv_file.write_csv(result, args.csv)
    if args.plot is not None:
        from reports import plotting

        plotting.plot(result, args.plot)
    if args.steps is None:
        print(json_report.to_json(json_report.with_warning(json_report.as_json(result), warning)) if args.json
              else text.final_report(result))
    return 0


def print_step_table(args, setup, model, warning) -> None:
    """--steps N: the first N updates, as a table or (--json) as JSON with the run's warning."""
    table = step_table.step_table(setup, model=model, integrator=args.integrator, steps=args.steps)
    if args.json:
        rows = table.pop("rows")
        print(json_report.to_json(json_report.with_warning({**table, "steps": args.steps, "step_table": rows},
                                                           warning)))
    else:
        print(step_table.format_step_table(table))


def write_programs(args, setup, model, *, warn: bool) -> None:
    """--vpython FILE.py, --webvpython FILE.py and --html FILE.html: the scene as a program to hand
    out, and as an offline page (export/).

    Every program is made and every path checked before any file is written, so bad input leaves
    no file at all. With `warn`, a Δt the program's motion will grow or blow up at is said on
    stderr (the program is still written: showing that may be the lesson).
    """
    import export

    if args.until is not None and args.until < model.until:   # the question time cannot be after the end
        setup = setup.with_values(until=float(args.until))
    if warn:
        try:
            warning = headless.stability_warning(model, model.methods(args.integrator))
        except BlowUpError as problem:
            warning = f"warning: {problem}; the program is written as asked"
        if warning:
            print(one_line(warning), file=sys.stderr)

    try:
        texts = [(path, export.program(setup, integrator=args.integrator, web=web, arrows=args.arrows,
                                       end=args.until))
                 for path, web in ((args.vpython, False), (args.webvpython, True)) if path is not None]
        for path, _ in texts:
            if path != "-":
                export.check_path(path, overwrite=args.overwrite)
        if args.html is not None:   # the offline page (export/offline_page.py), checked with the programs
            from export import offline_page

            if args.html != "-":
                offline_page.check_page_path(args.html, overwrite=args.overwrite)
            texts.append((args.html, offline_page.page(setup, integrator=args.integrator, arrows=args.arrows,
                                                       end=args.until)))
        if args.vpython not in (None, "-") and os.path.basename(args.vpython).lower() in ("vpython.py", "vpython.pyw"):
            raise UsageError(f"a program called {os.path.basename(args.vpython)} cannot run: its "
                             f"`from vpython import *` would import the program itself instead of the vpython "
                             f"library; give it another name, like spring.py")
        for path, program_text in texts:
            if path == "-":   # printed as a file would be written: with its mark and fingerprint
                print(files.stamped(program_text), end="")
            elif path == args.html:
                offline_page.write_page(path, program_text, overwrite=args.overwrite)
                print(f"wrote {path}", file=sys.stderr)
            else:
                export.write_program(path, program_text, overwrite=args.overwrite)
                print(f"wrote {one_line(path)}", file=sys.stderr)
    except ValueError as problem:   # export.ProgramError, or constants the physics cannot take
        raise UsageError(str(problem)) from None


def main(argv=None) -> int:
    args = build_parser().parse_args(argv)
    try:
        check_options(args)
        if args.list:
            listing, problems = text.list_scenes()
            print(listing)
            for problem in problems:  # the other scenes are listed, and run, as usual
                print(f"error: {one_line(str(problem))}", file=sys.stderr)
            return 2 if problems else 0
        setup = catalog.configure(catalog.DEFAULT_SCENE if args.scene is None else args.scene,
                                  assignments=args.assignments,
                                  scenario=args.scenario, preset=args.preset, forces=args.added_forces)
        if args.constants or args.forces:
            if args.constants:
                print(text.constants_report(setup))
                print(text.presets_report(setup))
            if args.forces:
                from reports.forces_report import forces_report

                print(forces_report(setup, build_model(args, setup)))
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
        if args.vpython is not None or args.webvpython is not None or args.html is not None:
            write_programs(args, setup, model, warn=not runs_headless)   # then a headless run too, if asked
            if not runs_headless:
                return 0
        if runs_headless:
            return run_headless(args, setup, model)
    except (ConstantError, DeclarationError, UsageError, files.OutputError, LabError) as problem:
        print(f"error: {one_line(str(problem))}", file=sys.stderr)
        return 2
    except BlowUpError as problem:
        print(f"error: {one_line(str(problem))}", file=sys.stderr)
        return 1
    from browser.clock import check_live_cost
    from browser.view import show

    try:
        check_live_cost(model, args.integrator)
    except ValueError as problem:
        print(f"error: {one_line(str(problem))}", file=sys.stderr)
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

    data = MeasuredData(fit_names=compare.check_names(setup, args.fit.split(",")) if args.fit else (),
                        coordinate=args.coordinate, sign=args.data_sign)
    data.measured = readers.read(args.data, column=args.data_column, run=args.run,
                                 coordinate=data.coordinate_for(setup))
    return data


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
        print(f"error: {one_line(str(problem))}", file=sys.stderr)
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
