"""The docstrings' examples run as written (doctest over the module, its
functions and its classes); a docstring example that fails, fails here."""

import doctest

import brdf


def test_docstring_examples_run():
    finder = doctest.DocTestFinder(exclude_empty=True)
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS)
    tests = finder.find(brdf, "brdf")
    for name in dir(brdf):
        obj = getattr(brdf, name)
        if callable(obj) and getattr(obj, "__doc__", None):
            tests += finder.find(obj, f"brdf.{name}", globs={})
    examples = sum(len(t.examples) for t in tests)
    assert examples >= 5, f"only {examples} docstring examples found"
    for t in tests:
        runner.run(t)
    result = runner.summarize(verbose=False)
    assert result.failed == 0, f"{result.failed} of {result.attempted} docstring examples failed"
