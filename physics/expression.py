"""A force written as one vector expression of the program's own names: its grammar, read safely.

A student adds a force on the page, or a teacher with `--force "push=vector(2, 0, 0)"`, by writing
its law as one expression, as the handed-out program would write the line `Fpush = ...`:

    vector(2, 0, 0)                                     a constant push, N
    -0.5*mag(v)*v                                       a wind, F = −½ |v| v
    -3/mag(r - vector(0,-4,0))**3 * (r - vector(0,-4,0))   a magnet 4 m below the origin

GRAMMAR is the one declaration of what may be written: the names (r, v, p, t and the scene's
constants m, k, b, g, dt, and pi), the functions (vector, mag, norm, hat, dot, cross, cos, sin,
exp, sqrt), which of them are vectors and which numbers, the operators + − × ÷ and **, and how a
number is spelled. Nothing else may appear: no attribute but the position's other names
(mass.pos), no subscripts, no keywords (import, lambda), no text in quotes, no unknown name.
`parse` reads a text by it in three passes, each refusing in one line the first thing it does not
allow:

1. tokens: every token matched by the grammar's own patterns must be a number, a name that is no
   Python keyword, or one of the allowed operators (a `^` says to write `**`);
2. syntax: Python's own parser (`ast.parse(text, mode="eval")`) reads the text, which is never run;
3. the tree: each node must be one the grammar has, and each name and function on its lists;
   then each operation must take and give what the grammar says (a number where a vector is
   needed is refused), and the whole must be a vector: a force.

The offline page has no Python: its script (export/force_box.js) reads GRAMMAR as data, written
into the page, and follows the same three passes with a small parser of its own; the tests hold
the two to the same answers (tests/test_force_grammar.py). The tree is what the engine evaluates
(physics/forces/written.py) and what `program_text` writes into the program, with the program's
names in place of the grammar's, so every front end runs the same arithmetic in the same order.
"""
from __future__ import annotations

import ast
import keyword
import re
import token
from dataclasses import dataclass

VECTOR, SCALAR = "vector", "number"

# ---- the grammar: plain data, read here and (as JSON) by the offline page's script ----

# The names an expression may use: what kind each is, and the other spellings of the position.
NAMES = {
    "r": {"kind": VECTOR, "aliases": ["pos", "ball.pos", "mass.pos"]},
    "v": {"kind": VECTOR, "aliases": []},
    "p": {"kind": VECTOR, "aliases": []},
    "t": {"kind": SCALAR, "aliases": []},
    "m": {"kind": SCALAR, "aliases": []},
    "k": {"kind": SCALAR, "aliases": []},
    "b": {"kind": SCALAR, "aliases": []},
    "g": {"kind": SCALAR, "aliases": []},
    "dt": {"kind": SCALAR, "aliases": []},
    "pi": {"kind": SCALAR, "aliases": []},
}
STATE_NAMES = ("r", "v", "p", "t", "m")      # given by the state at each step (p = m v)
CONSTANT_NAMES = ("k", "b", "g", "dt")       # the scene's constants: a scene that has them gives their values
# What each function takes and gives.
FUNCTIONS = {
    "vector": {"takes": [SCALAR, SCALAR, SCALAR], "gives": VECTOR},
    "mag": {"takes": [VECTOR], "gives": SCALAR},
    "norm": {"takes": [VECTOR], "gives": VECTOR},
    "hat": {"takes": [VECTOR], "gives": VECTOR},
    "dot": {"takes": [VECTOR, VECTOR], "gives": SCALAR},
    "cross": {"takes": [VECTOR, VECTOR], "gives": VECTOR},
    "cos": {"takes": [SCALAR], "gives": SCALAR},
    "sin": {"takes": [SCALAR], "gives": SCALAR},
    "exp": {"takes": [SCALAR], "gives": SCALAR},
    "sqrt": {"takes": [SCALAR], "gives": SCALAR},
}
# What each operator takes, as "left right" kinds, and gives.
BINARY = {
    "+": {f"{SCALAR} {SCALAR}": SCALAR, f"{VECTOR} {VECTOR}": VECTOR},
    "-": {f"{SCALAR} {SCALAR}": SCALAR, f"{VECTOR} {VECTOR}": VECTOR},
    "*": {f"{SCALAR} {SCALAR}": SCALAR, f"{SCALAR} {VECTOR}": VECTOR, f"{VECTOR} {SCALAR}": VECTOR},
    "/": {f"{SCALAR} {SCALAR}": SCALAR, f"{VECTOR} {SCALAR}": VECTOR},
    "**": {f"{SCALAR} {SCALAR}": SCALAR},
}
UNARY = {"-": {SCALAR: SCALAR, VECTOR: VECTOR}, "+": {SCALAR: SCALAR, VECTOR: VECTOR}}   # +x is x itself
BINARY_WORDS = {"+": "add", "-": "subtract", "*": "multiply", "/": "divide", "**": "raise to a power"}
# The tokens: patterns tried in this order at each place in the text (whitespace skipped).
TOKENS = {
    "number": r"(?:[0-9]|\.[0-9])(?:[eE][+-][0-9]|[0-9A-Za-z_.])*",
    "name": r"[A-Za-z_][A-Za-z0-9_]*",
    "quote": r"[\"']",
}
NUMBER = r"(?:[0-9]+\.?[0-9]*|\.[0-9]+)[eE][+-]?[0-9]+|[0-9]+\.[0-9]*|\.[0-9]+|0+|[1-9][0-9]*"
ALLOWED_OPERATORS = ["+", "-", "*", "/", "**", "(", ")", ",", "."]
# Python's operator tokens, longest first: a token is the longest of these at its place.
PYTHON_OPERATORS = sorted((text for text in token.EXACT_TOKEN_TYPES if text.strip()), key=lambda s: (-len(s), s))
HINTS = {"^": "write ** for a power", "−": "write - for minus", "×": "write * to multiply",
         "·": "write * to multiply", "[": "write v.x as dot(v, vector(1, 0, 0))", "=": "write only the force, "
         "its name goes in the name box", "==": "a force cannot compare", "%": "a force has no remainder",
         "//": "write / to divide"}
FORCE_NAME = r"[A-Za-z][A-Za-z0-9_]{0,19}"
MAX_LENGTH = 300
EXAMPLES = [
    {"name": "push", "text": "vector(2, 0, 0)", "what": "a constant push"},
    {"name": "wind", "text": "-0.5*mag(v)*v", "what": "a wind (air drag)"},
    {"name": "magnet", "text": "-3/mag(r - vector(0,-4,0))**3 * (r - vector(0,-4,0))", "what": "a magnet below the mass"},
]


def grammar() -> dict:
    """The grammar as JSON-ready data: what the offline page's script reads (export/force_box.js)."""
    return {"names": NAMES, "constants": list(CONSTANT_NAMES), "functions": FUNCTIONS, "binary": BINARY,
            "unary": UNARY, "binary_words": BINARY_WORDS, "tokens": TOKENS, "number": NUMBER,
            "allowed_operators": ALLOWED_OPERATORS, "python_operators": PYTHON_OPERATORS,
            "keywords": sorted(keyword.kwlist + keyword.softkwlist), "hints": HINTS, "force_name": FORCE_NAME,
            "max_length": MAX_LENGTH, "syntax_words": SYNTAX_WORDS, "syntax_default": SYNTAX_DEFAULT, "vector": VECTOR, "scalar": SCALAR, "examples": EXAMPLES}


class ExpressionError(ValueError):
    """A force that cannot be read: one line, naming the first thing not allowed."""


# ---- the tree ----

@dataclass(frozen=True)
class Number:
    text: str          # as written: the program writes it so
    kind = SCALAR


@dataclass(frozen=True)
class Name:
    name: str          # the grammar's own name (r for pos and mass.pos)
    kind: str


@dataclass(frozen=True)
class Unary:
    op: str
    operand: object
    kind: str


@dataclass(frozen=True)
class Binary:
    op: str
    left: object
    right: object
    kind: str


@dataclass(frozen=True)
class Call:
    function: str
    args: tuple
    kind: str


def names_in(node) -> set[str]:
    """The grammar names a tree reads."""
    if isinstance(node, Name):
        return {node.name}
    children = (node.operand,) if isinstance(node, Unary) else (node.left, node.right) if isinstance(node, Binary) \
        else node.args if isinstance(node, Call) else ()
    return set().union(*(names_in(child) for child in children)) if children else set()


# ---- reading a text ----

def _aliases() -> dict[str, str]:
    return {alias: name for name, named in NAMES.items() for alias in [name, *named["aliases"]]}


def tokens(text: str) -> list[tuple[str, str, int]]:
    """The text's tokens as (kind, text, start): kinds number, name, quote, operator, other."""
    found, at = [], 0
    patterns = [(kind, re.compile(pattern)) for kind, pattern in TOKENS.items()]
    while at < len(text):
        if text[at].isspace():
            at += 1
            continue
        for kind, pattern in patterns:
            match = pattern.match(text, at)
            if match:
                found.append((kind, match.group(), at))
                at = match.end()
                break
        else:
            operator = next((op for op in PYTHON_OPERATORS if text.startswith(op, at)), text[at])
            found.append(("operator" if operator in PYTHON_OPERATORS else "other", operator, at))
            at += len(operator)
    return found


def _check_tokens(text: str) -> None:
    """Pass 1: every token a number, a name that is no keyword, or an allowed operator."""
    number = re.compile(f"(?:{NUMBER})$")
    keywords = set(keyword.kwlist + keyword.softkwlist)
    for kind, word, _ in tokens(text):
        if kind == "number" and not number.match(word):
            raise ExpressionError(f"{word} is not a number this can read: write numbers like 2, 0.5 or 1e-3")
        if kind == "name" and word in keywords:
            raise ExpressionError(f"the word {word} is not allowed: write one force, like vector(2, 0, 0)")
        if kind == "quote":
            raise ExpressionError("text in quotes is not allowed: write one force, like vector(2, 0, 0)")
        if kind in ("operator", "other") and word not in ALLOWED_OPERATORS:
            hint = HINTS.get(word, "use + - * / ** and ( )")
            raise ExpressionError(f"{word} is not allowed: {hint}")


def _segment(text: str, node: ast.AST) -> str:
    return ast.get_source_segment(text, node) or ""


def _dotted(node: ast.AST) -> str | None:
    """a.b.c for a chain of names and attributes, else None."""
    if isinstance(node, ast.Name):
        return node.id
    if isinstance(node, ast.Attribute):
        head = _dotted(node.value)
        return None if head is None else f"{head}.{node.attr}"
    return None


def _known_names() -> str:
    return ", ".join(NAMES)


def _refusals(text: str, node: ast.AST, found: list) -> None:
    """Pass 3a: each node the grammar does not have, with its start, in the order of the tree (a
    node before the nodes inside it)."""
    start = getattr(node, "col_offset", 0)
    aliases = _aliases()
    if isinstance(node, (ast.Name, ast.Attribute)):
        dotted = _dotted(node)
        if dotted is None:
            found.append((start, f"{_segment(text, node)} is not allowed: a force may use the names {_known_names()}"))
            return
        if dotted in aliases:
            return
        if dotted in FUNCTIONS:
            found.append((start, f"{dotted} is a function: write it with what it works on, like {dotted}(v)"))
        elif "." in dotted:
            head, _, part = dotted.rpartition(".")
            hint = (f"for {dotted} write dot({head}, vector({', '.join('1' if axis == part else '0' for axis in 'xyz')}))"
                    if head in aliases and part in ("x", "y", "z") else f"a force may use the names {_known_names()}")
            found.append((start, f"{dotted} is not allowed: {hint}"))
        else:
            found.append((start, f"unknown name {dotted}: a force may use the names {_known_names()}"))
        return
    if isinstance(node, ast.Call):
        dotted = _dotted(node.func)
        if dotted not in FUNCTIONS:
            what = (f"{dotted} is not a function" if dotted in aliases else f"unknown function {dotted}" if dotted
                    else f"{_segment(text, node.func)} cannot be called")
            found.append((start, f"{what}: a force may use the functions {', '.join(FUNCTIONS)}"))
            return
        for arg in node.args:
            _refusals(text, arg, found)
        for keyword_arg in node.keywords:    # f(**a): `=` is refused with the tokens
            found.append((keyword_arg.col_offset, f"{_segment(text, keyword_arg)} is not allowed: give each value on its own"))
        return
    if isinstance(node, ast.Starred):
        found.append((start, f"{_segment(text, node)} is not allowed: give each value on its own"))
        return
    if isinstance(node, ast.Tuple):
        found.append((start, f"{_segment(text, node) or '()'} is a list of values, not a force: write vector(x, y, z)"))
        return
    if isinstance(node, ast.Constant):
        if not isinstance(node.value, (int, float)) or isinstance(node.value, bool):
            found.append((start, f"unknown name {_segment(text, node)}: a force may use the names {_known_names()}"))
        return
    if isinstance(node, ast.BinOp):
        _refusals(text, node.left, found)
        _refusals(text, node.right, found)
        return
    if isinstance(node, ast.UnaryOp):
        _refusals(text, node.operand, found)
        return
    found.append((start, f"{_segment(text, node)} is not allowed: write one force, like vector(2, 0, 0)"))


_BINARY_OPS = {ast.Add: "+", ast.Sub: "-", ast.Mult: "*", ast.Div: "/", ast.Pow: "**"}


def _tree(text: str, node: ast.AST):
    """Pass 3b: the grammar's tree, each node's kind worked out from its parts (bottom up, left
    before right); a part of the wrong kind is refused."""
    if isinstance(node, ast.Constant):
        return Number(_segment(text, node))
    if isinstance(node, (ast.Name, ast.Attribute)):
        name = _aliases()[_dotted(node)]
        return Name(name, NAMES[name]["kind"])
    if isinstance(node, ast.UnaryOp):
        operand = _tree(text, node.operand)
        if isinstance(node.op, ast.UAdd):      # +x is x: the tree has no unary plus
            return operand
        return Unary("-", operand, UNARY["-"][operand.kind])
    if isinstance(node, ast.BinOp):
        left, right = _tree(text, node.left), _tree(text, node.right)
        op = _BINARY_OPS.get(type(node.op))
        kind = BINARY[op].get(f"{left.kind} {right.kind}") if op else None
        if kind is None:
            raise ExpressionError(kind_message(op, left.kind, right.kind, _segment(text, node)))
        return Binary(op, left, right, kind)
    name = _dotted(node.func)
    takes = FUNCTIONS[name]["takes"]
    args = tuple(_tree(text, arg) for arg in node.args)
    if len(args) != len(takes):
        raise ExpressionError(arity_message(name, len(args), _segment(text, node)))
    for arg, kind, source in zip(args, takes, node.args):
        if arg.kind != kind:
            raise ExpressionError(f"{name} needs {_a(kind)}, and {_segment(text, source)} is {_a(arg.kind)}")
    return Call(name, args, FUNCTIONS[name]["gives"])


def _a(kind: str) -> str:
    return f"a {kind}"


def kind_message(op: str | None, left: str, right: str, segment: str) -> str:
    """Why `segment` cannot be worked out: its operator does not take these kinds."""
    if op is None:
        return f"{segment} is not allowed: use + - * / **"
    if op == "**":
        return f"cannot {BINARY_WORDS[op]} with a vector in {segment}: ** takes numbers (write mag(r)**3, not r**3)"
    if op == "/" and right == VECTOR:
        return f"cannot divide by a vector in {segment}: divide by a number, like mag(r)"
    if op == "*":
        return f"cannot multiply two vectors in {segment}: use dot(a, b) or cross(a, b)"
    return f"cannot {BINARY_WORDS[op]} {_a(left)} and {_a(right)} in {segment}: both must be vectors, or both numbers"


def arity_message(name: str, count: int, segment: str) -> str:
    takes = FUNCTIONS[name]["takes"]
    return (f"{name} takes {len(takes)} value{'s' if len(takes) != 1 else ''} ({', '.join(takes)}), "
            f"and {segment} gives it {count}")


@dataclass(frozen=True)
class Expression:
    """A force's law as read: the text (whitespace as one space), its tree, and the names it reads."""

    text: str
    tree: object

    @property
    def names(self) -> set[str]:
        return names_in(self.tree)


def parse(text: str) -> Expression:
    """The force written in `text`, read by GRAMMAR. Raises ExpressionError (one line) naming the
    first thing not allowed, a slip of syntax, or a number where a vector is needed."""
    text = " ".join(str(text).split())
    if not text:
        raise ExpressionError("write a force, like vector(2, 0, 0)")
    if len(text) > MAX_LENGTH:
        raise ExpressionError(f"a force of at most {MAX_LENGTH} characters, please (this one has {len(text)})")
    _check_tokens(text)
    try:
        tree = ast.parse(text, mode="eval").body
    except SyntaxError as problem:
        raise ExpressionError(syntax_message(problem.msg)) from None
    found: list = []
    _refusals(text, tree, found)
    if found:
        raise ExpressionError(min(found, key=lambda item: item[0])[1])
    read = _tree(text, tree)
    if read.kind != VECTOR:
        raise ExpressionError(f"{text} is a number, but a force is a vector: give it a direction, "
                              f"like ({text})*vector(0, 1, 0) or ({text})*hat(v)")
    return Expression(text, read)


SYNTAX_WORDS = {"'(' was never closed": "a ( is not closed", "unmatched ')'": "a ) has no ( before it",
                "Perhaps you forgot a comma?": "a comma may be missing"}
SYNTAX_DEFAULT = "check that each ( has its ) and each operator a value on both sides"


def syntax_message(what: str) -> str:
    """A slip of syntax, in Python's words where they help a student (SYNTAX_WORDS), else SYNTAX_DEFAULT."""
    said = next((words for python, words in SYNTAX_WORDS.items() if python in what), SYNTAX_DEFAULT)
    return f"cannot read the force: {said}"


def check_force_name(name: str, *, taken=()) -> str:
    """A force's name as given (its arrow's label; F_name in the program), or ExpressionError:
    letters, digits and _, starting with a letter, at most 20, and not one of `taken` (the
    labels of the forces already there)."""
    name = str(name).strip()
    if not re.fullmatch(FORCE_NAME, name):
        raise ExpressionError(f"a force's name is a word of letters, digits and _ that starts with a letter, "
                              f"at most 20 long, like push (got {name!r})")
    if name in taken:
        raise ExpressionError(f"the name {name} is taken: call the force something else, like my{name}")
    return name


# ---- writing it as a line of the program ----

_PRECEDENCE = {"+": 1, "-": 1, "*": 2, "/": 2, "unary": 3, "**": 4}


def _precedence(node) -> int:
    if isinstance(node, Binary):
        return _PRECEDENCE[node.op]
    return _PRECEDENCE["unary"] if isinstance(node, Unary) else 5


def program_text(node, spelled: dict[str, str]) -> str:
    """The tree as the program writes it, with each grammar name spelled as `spelled` says (r as
    pos, p as (m*v)): + and − spaced, × ÷ ** tight, and brackets where the order of the
    arithmetic needs them, and where Python and GlowScript would read it differently: a unary
    minus in the middle of a product, or on a power, has its own, (−x) and −(x**2), and a power of
    a power is 2**(3**2) (GlowScript 3.2 reads 2**3**2 as (2**3)**2). The offline page's script
    writes the same text (export/force_box.js)."""
    if isinstance(node, Number):
        return node.text
    if isinstance(node, Name):
        return spelled[node.name]
    if isinstance(node, Call):
        return f"{node.function}({', '.join(program_text(arg, spelled) for arg in node.args)})"
    if isinstance(node, Unary):
        inner = program_text(node.operand, spelled)
        return f"{node.op}({inner})" if isinstance(node.operand, (Binary, Unary)) else f"{node.op}{inner}"
    own = _PRECEDENCE[node.op]
    left, right = program_text(node.left, spelled), program_text(node.right, spelled)
    if _precedence(node.left) < own or (node.op == "**" and _precedence(node.left) <= own):
        left = f"({left})"
    if isinstance(node.right, Unary) or _precedence(node.right) <= own:   # GlowScript reads 2**3**2 as (2**3)**2
        right = f"({right})"
    return f"{left} {node.op} {right}" if node.op in ("+", "-") else f"{left}{node.op}{right}"
