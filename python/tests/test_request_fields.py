"""Issue #47: Python's keywords and the .pyi against the render request's rows
(request/request_fields.h): a setting with a Python name is a keyword where its row says, in the
compiled module and in the stub, and the docs state the row's default."""

import ast

import pytest

import omnicam
from omnicam import _omnicam


def _keywords_of_compiled(function):
    # pybind11 states the signature on the docstring's first line: "name(self: ..., kw: T = d, ...)".
    first = function.__doc__.splitlines()[0]
    inside = first[first.index("(") + 1: first.rindex(")")]
    names, depth, current = [], 0, ""
    for ch in inside + ",":
        if ch in "([":
            depth += 1
        elif ch in ")]":
            depth -= 1
        if ch == "," and depth == 0:
            names.append(current.strip().split(":")[0].split("=")[0].strip())
            current = ""
        else:
            current += ch
    return {n for n in names if n and n not in ("self", "*")}


def _keywords_of_stub(source, cls, name):
    tree = ast.parse((source / "python/omnicam/_omnicam.pyi").read_text())
    scope = tree.body
    if cls:
        scope = next(node.body for node in tree.body if isinstance(node, ast.ClassDef) and node.name == cls)
    function = next(node for node in scope if isinstance(node, ast.FunctionDef) and node.name == name)
    args = function.args
    return {a.arg for a in args.posonlyargs + args.args + args.kwonlyargs}


def _places():
    return {
        "Renderer": [(_omnicam.Renderer.__init__, "Renderer", "__init__")],
        "render": [(_omnicam.Renderer.render, "Renderer", "render"), (_omnicam.render, None, "render")],
    }


def test_every_python_row_is_a_keyword_where_its_row_says(source):
    rows = omnicam._omnicam._request_fields()
    assert len(rows) == 15
    places = _places()
    for row in rows:
        if not row["place"]:
            continue
        for function, cls, name in places[row["place"]]:
            assert row["python"] in _keywords_of_compiled(function), f"{name} has no keyword {row['python']}"
            assert row["python"] in _keywords_of_stub(source, cls, name), f"the .pyi's {cls}.{name} has no {row['python']}"


def test_the_settings_table_states_each_rows_default(source):
    table = (source / "docs/render-settings.md").read_text()
    for row in omnicam._omnicam._request_fields():
        line = next(line for line in table.splitlines() if line.startswith(f"| `{row['python']}`"))
        assert f"| {row['default']} |" in line, line


def test_a_bad_keyword_value_names_the_keyword(robocup):
    # The library's messages name a setting by its Python keyword (the rows' python name).
    for kwargs, name in [({"spp": 3}, "spp"), ({"shading": "shiny"}, "shading"), ({"bounces": 3}, "bounces"),
                         ({"seed": 1, "shading": "path", "denoise": True, "bounces": 99}, "bounces")]:
        with pytest.raises(omnicam.InputError) as caught:
            omnicam.render(robocup, size=32, **kwargs)
        assert str(caught.value).startswith(name + ":"), str(caught.value)
