"""The handed-out program's arrows, as the page draws them: p, F_net, each force and F∥/F⊥.

The program (export/vpython_program.py) gets, after its objects, the two scales (the page's, from
export/arrows.py, written in a comment) and the arrows `--arrows` asked for, per mass, in the
page's colours (export/palette.py); and, in its loop right after each mass's update, the lines
that move them:

    pscale = 1/20          # m per kg·m/s: an arrow 1 m long is 20 kg·m/s
    parrow = arrow(pos=pos, axis=pscale*p, color=vector(0.95, 0.88, 0.2), shaftwidth=0.2*radius)
    ...
        parrow.pos = pos
        parrow.axis = pscale*p                  # the momentum just updated

F_net's arrow shows Fnet, the net force the update just used. "forces" puts each force the update
added up (Fspring, Fgravity, ... in the order of Fnet's sum) on its own thin grey arrow, tip to
tail, so the last ends at F_net's tip, with its name (`spring`) beside its middle. "split" draws
F∥ = (F_net·p̂) p̂ (sky blue, it changes the speed) and F⊥ = F_net − F∥ (white, it changes the
direction), each labelled at its tip with its size (`F∥ = 3.95 N`, PART_DIGITS); from rest (p = 0) F∥ is all of
F_net, as on the page (export/arrows.py's split). Labels are 18 px, as on the page. The arrows
only read the state, so the program's arithmetic stays the engine's. The lines keep to what
GlowScript 3.2 (Web VPython) reads: no f-strings, no conditional expressions, lists made with
append.
"""
from __future__ import annotations

from .arrows import ARROWS, LABEL_PX, PART_DIGITS, SEE_THROUGH, choose_scales, force_name
from .lines import commented
from .palette import ARROW_COLOURS

WRITTEN = ARROWS   # the arrows a program draws: all the page's (p, F_net, forces, split)
SHAFT, THIN = "0.2*radius", "0.12*radius"   # shaft widths, as on the page (browser/arrows3d.py)


def _colour(kind: str) -> str:
    return "vector(" + ", ".join(f"{c:g}" for c in ARROW_COLOURS[kind]) + ")"


def _arrow(kind: str, *, at: str, axis: str = "vector(0, 0, 0)", shaft: str = SHAFT) -> str:
    return f"arrow(pos={at}, axis={axis}, color={_colour(kind)}, shaftwidth={shaft})"


def _label(kind: str, *, at: str, text: str, below: bool = False, side: tuple = ()) -> str:
    """A label in the arrow's colour, as the page's: 18 px, right of its point (F⊥'s below it), or
    on the side named by the expressions side = (xoffset, align)."""
    yoffset = -LABEL_PX["yoffset"] if below else LABEL_PX["yoffset"]
    xoffset, align = side or (LABEL_PX["xoffset"], '"left"')
    return (f"label(pos={at}, text={text}, height={LABEL_PX['height']}, color={_colour(kind)}, box=False, "
            f"line=False, xoffset={xoffset}, align={align}, yoffset={yoffset})")


def _made(name: str, make: str, *, single: bool, comment: str) -> list[str]:
    """`name = arrow(...)` for one mass, else the list `names` with one such arrow per mass."""
    if single:
        return [commented(f"{name} = {make}", comment)]
    return [commented(f"{name}s = []", comment), "for i in range(len(pos)):",
            f"    {name}s.append({make.replace('pos=pos', 'pos=pos[i]').replace('*p,', '*p[i],')})"]


def _made_per_force(model, *, single: bool) -> list[str]:
    """forcearrows: a thin grey arrow per force (per mass: forcearrows[i]), in the order of Fnet's sum."""
    at = "pos" if single else "pos[i]"
    make = _arrow("forces", at=at, shaft=THIN)
    named = _label("forces", at=at, text="forcenames[j]", side=("forcexoffsets[j]", "forcealigns[j]"))
    names = ", ".join(force_name(force) for force in model.forces)
    count = len(model.forces)
    each = f"for j in range({count}):"
    x = LABEL_PX["xoffset"]
    lines = [commented("forcearrows = []", f"grey, tip to tail, one per force: {names}"),
             commented("forcelabels = []", "each force's name beside its arrow, every other one on the left"),
             "forcenames = [" + ", ".join(f'"{force_name(force)}"' for force in model.forces) + "]",
             "forcexoffsets = [" + ", ".join(str(-x if j % 2 else x) for j in range(count)) + "]",
             "forcealigns = [" + ", ".join('"right"' if j % 2 else '"left"' for j in range(count)) + "]"]
    if single:
        return lines + [each, f"    forcearrows.append({make})", f"    forcelabels.append({named})"]
    return lines + ["for i in range(len(pos)):", "    forcearrows.append([])", "    forcelabels.append([])",
                    f"    {each}", f"        forcearrows[i].append({make})", f"        forcelabels[i].append({named})"]


def setup_lines(model, *, shown, integrator: str | None, single: bool, view: dict, written=None,
                scales=None) -> list[str]:
    """The scales (the page's, for the scene's view and the arrows `shown`) and the arrows, made
    where each mass starts (after the program's objects): those shown, or all those `written`
    (the offline page, whose check boxes show and hide them)."""
    kinds = [kind for kind in WRITTEN if kind in (shown if written is None else written)]
    if not kinds:
        return []
    if scales is None:   # else chosen already (the offline page's programs share the file's)
        scales = choose_scales(model, view=view, integrator=integrator, forces="forces" in shown)
    lines = ["", f"# ---- the arrows: {', '.join(kinds)} at fixed scales, as on the page ----"]
    see_through = "see-through, as on the page: an arrow shorter than the radius shows inside"
    if single:
        lines.append(commented(f"ball.opacity = {SEE_THROUGH:g}", see_through))
    else:
        lines += [commented("for each in balls:", see_through), f"    each.opacity = {SEE_THROUGH:g}"]
    if "p" in kinds:
        lines.append(commented(f"pscale = 1/{scales.p_unit:g}",
                               f"m per kg·m/s: an arrow 1 m long is {scales.p_unit:g} kg·m/s"))
    if set(kinds) - {"p"}:
        lines.append(commented(f"Fscale = 1/{scales.F_unit:g}", f"m per N: an arrow 1 m long is {scales.F_unit:g} N"))
    if "p" in kinds:
        lines += _made("parrow", _arrow("p", at="pos", axis="pscale*p"), single=single, comment="yellow: momentum p")
    if "F_net" in kinds:   # from the first update on
        lines += _made("Farrow", _arrow("F_net", at="pos"), single=single, comment="reddish purple: net force")
    if "forces" in kinds:
        lines += _made_per_force(model, single=single)
    if "split" in kinds:
        lines += _made("pararrow", _arrow("F_par", at="pos"), single=single, comment="sky blue: F∥, along p")
        lines += _made("perparrow", _arrow("F_perp", at="pos"), single=single, comment="white: F⊥, across p")
        lines += _made("parlabel", _label("F_par", at="pos", text='"F∥"'), single=single,
                       comment="F∥ and its size, at its tip")
        lines += _made("perplabel", _label("F_perp", at="pos", text='"F⊥"', below=True), single=single,
                       comment="F⊥ and its size, below its tip")
    return lines


def loop_lines(model, *, shown, single: bool) -> list[str]:
    """Each arrow moved to its mass and its quantity, right after the mass's update."""
    i = "" if single else "[i]"
    each = "" if single else "s[i]"
    lines = []
    if "p" in shown:
        lines += [f"parrow{each}.pos = pos{i}",
                  commented(f"parrow{each}.axis = pscale*p{i}", "the momentum just updated")]
    if "F_net" in shown:
        lines += [f"Farrow{each}.pos = pos{i}",
                  commented(f"Farrow{each}.axis = Fscale*Fnet", "the net force the update used")]
    if "forces" in shown:
        lines.append(commented(f"Ftail = pos{i}", "each force from the tip of the one before"))
        for n, force in enumerate(model.forces):
            lines += [f"forcearrows{i}[{n}].pos = Ftail", f"forcearrows{i}[{n}].axis = Fscale*{force.TERM}",
                      f"forcelabels{i}[{n}].pos = Ftail + 0.5*Fscale*{force.TERM}",
                      f"Ftail = Ftail + Fscale*{force.TERM}"]
    if "split" in shown:
        lines += [commented(f"phat = norm(p{i})", "the direction of p"),
                  f"if mag(p{i}) == 0:",
                  commented("    phat = norm(Fnet)", "from rest: all of F_net starts the motion"),
                  commented("Fpar = dot(Fnet, phat)*phat", "F∥ = (F_net·p̂) p̂: changes the speed"),
                  commented("Fperp = Fnet - Fpar", "F⊥ = F_net − F∥: changes the direction")]
        for name, part, symbol in (("par", "Fpar", "F∥"), ("perp", "Fperp", "F⊥")):
            lines += [f"{name}arrow{each}.pos = pos{i}", f"{name}arrow{each}.axis = Fscale*{part}",
                      f"{name}label{each}.pos = pos{i} + Fscale*{part}",
                      f'{name}label{each}.text = "{symbol} = {PART_DIGITS} N".format(mag({part}))']
    return lines
