"""The examples in the docstrings and in docs/python.md run and print what they show."""

import doctest
import inspect

import pytest

import pliant
from conftest import REPO


def _docstrings():
    """(name, docstring) of the package, its functions, classes and their members."""
    yield "pliant", pliant.__doc__
    for name in pliant.__all__:
        obj = getattr(pliant, name)
        if callable(obj) and obj.__doc__:
            yield f"pliant.{name}", obj.__doc__
        if inspect.isclass(obj):
            for member in vars(obj):
                doc = getattr(getattr(obj, member), "__doc__", None)
                if not member.startswith("_") and doc and ">>>" in doc:
                    yield f"pliant.{name}.{member}", doc


EXAMPLES = [(n, d) for n, d in _docstrings() if d and ">>>" in d]


def test_there_are_examples():
    assert len(EXAMPLES) >= 15, [n for n, _ in EXAMPLES]


@pytest.mark.parametrize("name,doc", EXAMPLES, ids=[n for n, _ in EXAMPLES])
def test_docstring_examples(name, doc):
    parser = doctest.DocTestParser()
    test = parser.get_doctest(doc, {}, name, None, 0)
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    runner.run(test)
    result = runner.summarize(verbose=False)
    assert result.failed == 0, f"{result.failed} example(s) of {name} failed (output above)"


def test_python_guide_examples(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    result = doctest.testfile(
        str(REPO / "docs" / "python.md"),
        module_relative=False,
        optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE,
    )
    assert result.attempted >= 10 and result.failed == 0
