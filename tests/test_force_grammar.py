"""The grammar a written force is read by (physics/expression.py): what it takes, what it refuses
in one line naming the first thing not allowed, and the program line it writes, which reads back
as the same tree (so the program does the engine's arithmetic in the engine's order)."""
from __future__ import annotations

import ast

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from physics.expression import (EXAMPLES, FUNCTIONS, NAMES, SCALAR, VECTOR, Binary, Call, ExpressionError, Name,
                                Number, Unary, check_force_name, grammar, parse, program_text)

PLAIN = {name: name for name in NAMES}


ACCEPTED = [
    ("vector(2, 0, 0)", "vector(2, 0, 0)"),
    ("-0.5*mag(v)*v", "-0.5*mag(v)*v"),
    ("-3/mag(r - vector(0,-4,0))**3 * (r - vector(0,-4,0))", "-3/mag(r - vector(0, -4, 0))**3*(r - vector(0, -4, 0))"),
    ("mass.pos*2", "r*2"),
    ("ball.pos + pos", "r + r"),
    ("+v", "v"),                                  # +x is x: the tree has no unary plus
    ("--v", "-(-v)"),                             # never `--v`, which JavaScript reads as a decrement
    ("-2**2*v", "-(2**2)*v"),                     # Python's order: −(2²)
    ("(-2)**2*v", "(-2)**2*v"),
    ("2**-1*v", "2**(-1)*v"),
    ("2**3**2*v", "2**(3**2)*v"),                 # ** groups from the right (GlowScript's would not)
    ("(2**3)**2*v", "(2**3)**2*v"),
    ("v - (v - r)", "v - (v - r)"),               # the order of the sums is kept
    ("(v - v) - r", "v - v - r"),
    ("1e-3*cross(v, vector(0, 0, 1))", "1e-3*cross(v, vector(0, 0, 1))"),
    ("vector(0, -m*g, 0) - k*r - b*v + dt*p + sqrt(pi)*exp(-t)*hat(r)*cos(t)*sin(t)*dot(r, v)",
     "vector(0, -m*g, 0) - k*r - b*v + dt*p + sqrt(pi)*exp(-t)*hat(r)*cos(t)*sin(t)*dot(r, v)"),
    ("  vector( 1 ,\t2, 3 )  ", "vector(1, 2, 3)"),
    (".5*norm(v)", ".5*norm(v)"),
]


@pytest.mark.parametrize("text, written", ACCEPTED)
def test_a_force_is_read_and_written_back_in_the_same_order(text, written):
    law = parse(text)
    assert law.tree.kind == VECTOR
    assert program_text(law.tree, PLAIN) == written
    assert parse(written).tree == law.tree


@pytest.mark.parametrize("example", EXAMPLES, ids=lambda example: example["name"])
def test_the_menu_examples_are_forces(example):
    assert parse(example["text"]).tree.kind == VECTOR


REFUSED = [
    ("", "write a force"),
    ("-0.5*mag(v)", "is a number, but a force is a vector"),
    ("v.x*vector(1,0,0)", "v.x is not allowed: for v.x write dot(v, vector(1, 0, 0))"),
    ("r.__class__", "r.__class__ is not allowed"),
    ("__import__('os')", "text in quotes is not allowed"),
    ("__import__(os)", "unknown function __import__"),
    ("lambda: v", "the word lambda is not allowed"),
    ("import os", "the word import is not allowed"),
    ("v if t else r", "the word if is not allowed"),
    ("v[0]", "[ is not allowed"),
    ("[v]", "[ is not allowed"),
    ("{v}", "{ is not allowed"),
    ("v == r", "== is not allowed"),
    ("v @ r", "@ is not allowed"),
    ("r % 2", "% is not allowed"),
    ("r // 2", "// is not allowed"),
    ("x := v", ":= is not allowed"),
    ("foo", "unknown name foo"),
    ("open(v)", "unknown function open"),
    ("mag", "mag is a function"),
    ("vector(1, 2)", "vector takes 3 values"),
    ("mag(v, v)*v", "mag takes 1 value"),
    ("vector(v, 0, 0)", "vector needs a number, and v is a vector"),
    ("cos(v)*v", "cos needs a number, and v is a vector"),
    ("mag(2)*v", "mag needs a vector, and 2 is a number"),
    ("r + 1", "cannot add a vector and a number in r + 1"),
    ("r*r", "cannot multiply two vectors in r*r"),
    ("2/r", "cannot divide by a vector in 2/r"),
    ("r**2", "cannot raise to a power with a vector in r**2"),
    ("r^2", "^ is not allowed: write ** for a power"),
    ("−v", "− is not allowed: write - for minus"),
    ("1_000*v", "1_000 is not a number"),
    ("01*v", "01 is not a number"),
    ("0x10*v", "0x10 is not a number"),
    ("2j*v", "2j is not a number"),
    ("True*v", "the word True is not allowed"),
    ("(1, 2)", "is a list of values"),
    ("v,", "is a list of values"),
    ("mag(*v)*v", "*v is not allowed"),
    ("mag(**v)*v", "**v is not allowed"),
    ("(v)(2)", "v is not a function"),
    ("mag(v)(2)", "mag(v) cannot be called"),
    ("1 .x*v", "is not allowed"),
    ("vector(2, 0, 0", "a ( is not closed"),
    ("mag(v))*v", "a ) has no ( before it"),
    ("vector(2 0 0)", "a comma may be missing"),
    ("2*", "cannot read the force"),
    ("v\nimport os", "the word import is not allowed"),
    ("$v", "$ is not allowed"),
    ("v # a comment", "# is not allowed"),
    ("x" * 301, "at most 300 characters"),
]


@pytest.mark.parametrize("text, said", REFUSED)
def test_anything_else_is_refused_in_one_line_naming_it(text, said):
    with pytest.raises(ExpressionError) as refused:
        parse(text)
    message = str(refused.value)
    assert said in message
    assert "\n" not in message and "Traceback" not in message


def test_the_first_thing_not_allowed_is_the_one_named():
    with pytest.raises(ExpressionError, match="unknown name foo"):
        parse("foo*v + bar(v) + v.y")
    with pytest.raises(ExpressionError, match="unknown function bar"):
        parse("bar(v) + foo*v")
    with pytest.raises(ExpressionError, match=r"\[ is not allowed"):      # the tokens are read first
        parse("foo*v + v[0]")


@pytest.mark.parametrize("name, ok", [("push", True), ("wind_2", True), ("M", True), ("2push", False),
                                      ("", False), ("a b", False), ("x" * 21, False), ("_x", False),
                                      ("spring", False), ("push", True)])
def test_a_force_name_is_a_word_not_taken(name, ok):
    if ok:
        assert check_force_name(name, taken=("spring", "gravity")) == name
    else:
        with pytest.raises(ExpressionError):
            check_force_name(name, taken=("spring", "gravity"))


def test_the_grammar_is_plain_data_for_the_offline_page():
    import json
    data = json.loads(json.dumps(grammar()))
    assert set(data["functions"]) == set(FUNCTIONS) and set(data["names"]) == set(NAMES)
    assert "import" in data["keywords"] and "**" in data["python_operators"]


# ---- any tree the grammar can make is written so that it reads back as itself ----

def _trees(kind: str):
    scalars = st.sampled_from([Name(n, SCALAR) for n, named in NAMES.items() if named["kind"] == SCALAR]
                              + [Number("2"), Number("0.5"), Number("3e-2")])
    vectors = st.sampled_from([Name(n, VECTOR) for n, named in NAMES.items() if named["kind"] == VECTOR])

    def extend(children):
        scalar, vector = children
        return st.one_of(
            st.builds(lambda a, op, b: Binary(op, a, b, SCALAR), scalar, st.sampled_from("+-*/") | st.just("**"), scalar),
            st.builds(lambda a: Unary("-", a, SCALAR), scalar),
            st.builds(lambda a: Call("mag", (a,), SCALAR), vector),
            st.builds(lambda a: Call("cos", (a,), SCALAR), scalar),
        ), st.one_of(
            st.builds(lambda a, op, b: Binary(op, a, b, VECTOR), vector, st.sampled_from("+-"), vector),
            st.builds(lambda a, b: Binary("*", a, b, VECTOR), scalar, vector),
            st.builds(lambda a, b: Binary("*", a, b, VECTOR), vector, scalar),
            st.builds(lambda a, b: Binary("/", a, b, VECTOR), vector, scalar),
            st.builds(lambda a: Unary("-", a, VECTOR), vector),
            st.builds(lambda a, b, c: Call("vector", (a, b, c), VECTOR), scalar, scalar, scalar),
            st.builds(lambda a, b: Call("cross", (a, b), VECTOR), vector, vector),
        )

    both = st.recursive(st.tuples(scalars, vectors), lambda children: st.tuples(*extend((
        children.map(lambda pair: pair[0]), children.map(lambda pair: pair[1])))), max_leaves=12)
    return both.map(lambda pair: pair[1] if kind == VECTOR else pair[0])


TREES = _trees(VECTOR)


@settings(max_examples=300, deadline=None)
@given(TREES)
def test_any_tree_reads_back_as_itself(tree):
    written = program_text(tree, PLAIN)
    assert parse(written).tree == tree
    ast.parse(written, mode="eval")             # and Python reads it too
