"""The code stays readable in pieces: no module of the package over 700 lines, and no function of the
one evaluation (pumplink/evaluate/) over 80 lines of code (docstrings, comments and blank lines
not counted), so each stage reads on one screen."""

from __future__ import annotations

import ast
import io
import tokenize

from tests.examples import ROOT

PACKAGE = ROOT / "pumplink"
MODULE_LINES, FUNCTION_CODE_LINES = 700, 80


def code_lines(source: str, node: ast.AST) -> int:
    """Lines of ``node`` that hold code: not blank, not only a comment, not its docstrings."""
    docs = set()
    for n in ast.walk(node):
        if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)) and ast.get_docstring(n):
            d = n.body[0]
            docs.update(range(d.lineno, d.end_lineno + 1))
    lines = source.splitlines()[node.lineno - 1 : node.end_lineno]
    text = "\n".join(lines) + "\n"
    code = set()
    for tok in tokenize.generate_tokens(io.StringIO(text).readline):
        if tok.type not in (tokenize.COMMENT, tokenize.NL, tokenize.NEWLINE, tokenize.INDENT,
                            tokenize.DEDENT, tokenize.ENDMARKER):  # fmt: skip
            code.update(range(tok.start[0], tok.end[0] + 1))
    return len({k + node.lineno - 1 for k in code} - docs)


def long_functions(source: str, limit: int) -> list[tuple[str, int]]:
    tree = ast.parse(source)
    return [
        (n.name, code_lines(source, n))
        for n in ast.walk(tree)
        if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef)) and code_lines(source, n) > limit
    ]


def test_no_module_over_700_lines():
    long = {str(p.relative_to(ROOT)): n for p in PACKAGE.rglob("*.py")
            if (n := len(p.read_text(encoding="utf-8").splitlines())) > MODULE_LINES}  # fmt: skip
    assert not long, long


def test_no_function_of_the_evaluation_over_80_lines_of_code():
    long = {
        f"{p.name}:{name}": n
        for p in sorted((PACKAGE / "evaluate").glob("*.py"))
        for name, n in long_functions(p.read_text(encoding="utf-8"), FUNCTION_CODE_LINES)
    }
    assert not long, long


def test_the_counter_counts_code_not_words():
    """A made-up function: 3 lines of code, a docstring, a comment and a blank line."""
    source = 'def f(x):\n    """Doc\n    string."""\n    # a comment\n\n    y = x + 1\n    return y\n'
    assert long_functions(source, 2) == [("f", 3)]
    assert long_functions(source, 3) == []
