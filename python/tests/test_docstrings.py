"""The examples in the package's docstrings are run and must hold."""

import doctest

import pytest

from triangle_rs import compat, data, meshing, report, triangulateio


@pytest.mark.parametrize("module", [compat, data, meshing, report, triangulateio], ids=lambda m: m.__name__)
def test_docstring_examples(module):
    result = doctest.testmod(module, optionflags=doctest.NORMALIZE_WHITESPACE)
    assert result.attempted > 0 and result.failed == 0
