"""Writing a measured-looking run the way each data program exports it (for examples/, the mystery
spring and the tests' fixtures). Each writer takes t in s and a position in m and returns the text.

    tracker    Tracker's Export Data: a line naming the track, then `t x y` (its delimiter: tab,
               comma, semicolon or space; a decimal comma with ; or tab)
    vernier    Vernier Graphical Analysis CSV: `Latest: Time (s),Latest: Position (m)`
    pasco      PASCO Capstone CSV: `Time (s) Run #1,Position (m) Run #1,...`, several runs side by side
               (with a European computer's settings: semicolons between cells, decimal commas)
    loggerpro  Logger Pro's text export: a title block, then names, symbols and units, tab-separated
    csv        this program's own --csv header `t,x,y,z,vx,...` (the other columns left empty)
    plain      two columns of numbers, t in s and position in m, and no header at all
"""
from __future__ import annotations

from export.numbers import CSV_HEADER

FORMATS = ("tracker", "vernier", "pasco", "loggerpro", "csv", "plain")


def _number(x: float, digits: int, comma: bool = False) -> str:
    text = f"{x:.{digits}f}"
    return text.replace(".", ",") if comma else text


def tracker(t, y, *, delimiter="\t", decimal_comma=False, track="mass A", x=None) -> str:
    """Tracker: the track's name, `t`, `x`, `y` (x is the horizontal position, 0 when not given)."""
    space = delimiter == " "
    lines = [track, delimiter.join(["t", "x", "y"])]
    for n, (time, height) in enumerate(zip(t, y)):
        across = 0.0 if x is None else x[n]
        lines.append(delimiter.join(_number(v, 4, decimal_comma and not space)
                                    for v in (time, across, height)))
    return "\r\n".join(lines) + "\r\n"


def vernier(t, y, *, time_unit="s", length_unit="m") -> str:
    """Vernier Graphical Analysis: one `Latest:` column each for time and position."""
    scale_t = {"s": 1.0, "ms": 1e3}[time_unit]
    scale_x = {"m": 1.0, "cm": 1e2, "mm": 1e3}[length_unit]
    lines = [f"Latest: Time ({time_unit}),Latest: Position ({length_unit})"]
    lines += [f"{time * scale_t:.6g},{height * scale_x:.6g}" for time, height in zip(t, y)]
    return "\n".join(lines) + "\n"


def pasco(runs, *, separator=",", decimal_comma=False) -> str:
    """PASCO Capstone: `runs` is a list of (t, y); a shorter run leaves its cells empty below its end."""
    header = []
    for number in range(1, len(runs) + 1):
        header += [f"Time (s) Run #{number}", f"Position (m) Run #{number}"]
    lines = [separator.join(header)]
    for row in range(max(len(t) for t, _ in runs)):
        cells = []
        for t, y in runs:
            cells += [_number(t[row], 4, decimal_comma), _number(y[row], 4, decimal_comma)] if row < len(t) else ["", ""]
        lines.append(separator.join(cells))
    return "\n".join(lines) + "\n"


def plain(t, y) -> str:
    """Two columns, t in s and position in m, separated by a space, with no header."""
    return "".join(f"{time:.4f} {height:.5f}\n" for time, height in zip(t, y))


def loggerpro(t, y) -> str:
    """Logger Pro's text export: a title block, names, symbols and units, then tab-separated rows."""
    lines = ["Vernier Format 2", "spring.cmbl", "Latest", "Time\tPosition", "t\tx", "s\tm", ""]
    lines += [f"{time:.4f}\t{height:.4f}" for time, height in zip(t, y)]
    return "\n".join(lines) + "\n"


def own_csv(t, y) -> str:
    """This program's --csv: its header, with t and y given and the other columns empty."""
    lines = [",".join(CSV_HEADER)]
    for time, height in zip(t, y):
        row = [""] * len(CSV_HEADER)
        row[0], row[2] = f"{time:.6g}", f"{height:.6g}"
        lines.append(",".join(row))
    return "\n".join(lines) + "\n"


def write_format(name: str, t, y) -> str:
    """The text of a run in format `name` (one of FORMATS), with each format's usual choices."""
    return {"tracker": lambda: tracker(t, y), "vernier": lambda: vernier(t, y),
            "pasco": lambda: pasco([(t, y)]), "loggerpro": lambda: loggerpro(t, y),
            "csv": lambda: own_csv(t, y), "plain": lambda: plain(t, y)}[name]()
