"""The book's chapter "From Python" (book/src/python.md): its Python code runs, in order, and
prints what the chapter shows. The figure's block runs with matplotlib's file backend."""

import contextlib
import io
import os
import re

import pytest

from conftest import ROOT

CHAPTER = ROOT / "book" / "src" / "python.md"


def blocks(fence):
    return re.findall(rf"```{fence}\n(.*?)```", CHAPTER.read_text(), re.S)


def test_the_chapter_runs_and_prints_what_it_shows(tmp_path, monkeypatch):
    pytest.importorskip("matplotlib")
    monkeypatch.setenv("MPLBACKEND", "Agg")
    monkeypatch.chdir(tmp_path)
    printed = io.StringIO()
    namespace = {}
    with contextlib.redirect_stdout(printed):
        for code in blocks("python"):
            exec(compile(code, str(CHAPTER), "exec"), namespace)
    shown = "".join(blocks("text"))
    assert printed.getvalue() == shown
    assert (tmp_path / "python_crown.svg").stat().st_size > 0
    assert os.path.exists(ROOT / "book" / "src" / "python_crown.svg")
