"""Printing on any terminal: a symbol the terminal's encoding cannot write is spelled in ASCII.

The reports use the textbook's symbols (Δt, ω = √(k/m), m/s², −1.73). A Windows console in cp1252,
a pipe in ASCII or a latin-1 locale cannot write some of them; rather than fail, each is written
the way a student would type it: Δt → dt, ω → omega, √ → sqrt, ² → ^2, − → -, · → *. Files the
program writes (CSV, programs) are always UTF-8 and are not touched.
"""
from __future__ import annotations

import codecs
import sys
import unicodedata

ERRORS = "spring_ascii"     # the codec error handler's name, for stream.reconfigure(errors=...)

SPELLED = {
    "Δ": "d", "δ": "d", "ω": "omega", "Ω": "Omega", "ρ": "rho", "γ": "gamma", "λ": "lambda", "π": "pi",
    "θ": "theta", "φ": "phi", "τ": "tau", "α": "alpha", "β": "beta", "µ": "u", "μ": "mu", "Σ": "sum",
    "∫": "integral", "∝": "~", "∘": "o", "√": "sqrt", "−": "-", "–": "-", "—": "-", "·": "*", "×": "x",
    "÷": "/", "±": "+/-", "≈": "~", "≤": "<=", "≥": ">=", "≠": "!=", "→": "->", "←": "<-", "…": "...",
    "½": "1/2", "¼": "1/4", "¾": "3/4", "°": " deg", "‘": "'", "’": "'", "“": '"', "”": '"', "⟨": "<",
    "⟩": ">", "∞": "infinity",
}
SUPERSCRIPTS = dict(zip("⁰¹²³⁴⁵⁶⁷⁸⁹⁻⁺ⁿ", "0123456789-+n"))
SUBSCRIPTS = dict(zip("₀₁₂₃₄₅₆₇₈₉₋₊", "0123456789-+"))


def spell(text: str) -> str:
    """`text` in ASCII: the symbols above spelled out, a run of superscripts as ^..., accents dropped."""
    out, n = [], 0
    while n < len(text):
        char = text[n]
        if char in SUPERSCRIPTS:   # m/s², s⁻¹, 10⁻⁶: one caret for the whole exponent
            end = n
            while end < len(text) and text[end] in SUPERSCRIPTS:
                end += 1
            out.append("^" + "".join(SUPERSCRIPTS[c] for c in text[n:end]))
            n = end
            continue
        if char in SPELLED:
            out.append(SPELLED[char])
        elif char in SUBSCRIPTS:
            out.append(SUBSCRIPTS[char])
        elif ord(char) < 128:
            out.append(char)
        else:   # û → u, é → e, a lone combining mark → nothing; anything else → ?
            plain = unicodedata.normalize("NFKD", char).encode("ascii", "ignore").decode()
            out.append(plain if plain or unicodedata.combining(char) else "?")
        n += 1
    return "".join(out)


def _spell_unencodable(error: UnicodeEncodeError):
    return spell(error.object[error.start:error.end]), error.end


codecs.register_error(ERRORS, _spell_unencodable)


def install() -> None:
    """Make sys.stdout and sys.stderr write what their encoding cannot as ASCII spellings."""
    for stream in (sys.stdout, sys.stderr):
        reconfigure = getattr(stream, "reconfigure", None)
        if reconfigure is not None:
            try:
                reconfigure(errors=ERRORS)
            except (ValueError, OSError):   # a closed or detached stream: nothing to print to anyway
                pass


class OutputStreamError(Exception):
    """Standard output is closed or cannot be written (a full disk, /dev/full): a one-line message."""


class GuardedOutput:
    """Standard output that says in one line why it cannot be written, instead of losing the output.

    `python main.py ... >&-` starts Python with no standard output at all (sys.stdout is None, and
    print() would drop the report without a word); a full disk fails part-way. A broken pipe
    (`| head`) is left as it is: main.run() ends that quietly, as a shell expects.
    """

    def __init__(self, stream):
        self.stream = stream

    def _guarded(self, action, *arguments):
        if self.stream is None:
            raise OutputStreamError("cannot print the output: standard output is closed (the command "
                                    "was started with >&- or without a console); redirect it to a file")
        try:
            return getattr(self.stream, action)(*arguments)
        except BrokenPipeError:
            raise
        except OSError as problem:
            raise OutputStreamError(f"cannot print the output: {problem.strerror or problem}") from None

    def write(self, text):
        return self._guarded("write", text)

    def flush(self):
        return self._guarded("flush") if self.stream is not None else None

    def __getattr__(self, name):
        return getattr(self.stream, name)


def discard_output(stream) -> None:
    """Point `stream`'s file at the null device, so Python's last flush at exit cannot fail again
    on what was left in its buffer (after a broken pipe or a full disk)."""
    import os

    try:
        os.dup2(os.open(os.devnull, os.O_WRONLY), stream.fileno())
    except (OSError, AttributeError, ValueError):   # no file under it (closed, or captured): nothing to flush
        pass
