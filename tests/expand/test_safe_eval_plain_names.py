"""A bare ``${name}`` skips the tree walk (expand/safe_eval._plain_name): it must take that path
exactly when the full vetting would accept it as one plain name with nothing to rewrite."""

import ast

import pytest

from myrabot_desc.expand.safe_eval import RefusedExpression, _calls_of, _needs_bound, _plain_name, check_expression

CASES = ["a", "ur_type", "wheel_radius", "_", "x1", "match", "case", "type", "print", "open", "é", "Ω2",
         "__x", "__import__", "_md_call", "_md_", "True", "False", "None", "lambda", "import", "not",
         "a.b", " a", "a ", "a+b", "1", "", "a()", "a[0]"]


def _full(expr):
    try:
        tree = check_expression(expr)
    except RefusedExpression:
        return False
    return isinstance(tree.body, ast.Name) and expr == expr.strip() and _calls_of(tree) == () and \
        not any(_needs_bound(n) for n in ast.walk(tree))


@pytest.mark.parametrize("expr", CASES)
def test_plain_name_path_agrees_with_full_vetting(expr):
    assert _plain_name(expr) == _full(expr)


@pytest.mark.parametrize("expr", ["__import__", "__builtins__", "_md_call"])
def test_refused_names_still_refused(expr):
    with pytest.raises(RefusedExpression):
        check_expression(expr)
    assert not _plain_name(expr)
