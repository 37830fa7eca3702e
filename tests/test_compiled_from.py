"""numba keeps a compiled function while the text of its own file is unchanged, though the
constants it reads and the functions it calls from other files are compiled into it.  Each
kernel file carries the digest of those other files, so that changing one (a tolerance in
``_codes.py``, a function of the kinematics kernel that the dynamics kernel calls) changes
the kernel file too and numba compiles afresh instead of loading code made with the old
numbers."""
import importlib

import pytest

from kinelab import _compiled


@pytest.mark.parametrize("kernel", sorted(_compiled._COMPILED_FROM))
def test_each_kernel_file_carries_the_digest_of_what_it_is_compiled_from(kernel):
    module = importlib.import_module("kinelab." + kernel.removesuffix(".py").replace("/", "."))
    expected = _compiled.compiled_from(kernel)
    assert module.COMPILED_FROM == expected, (
        f"kinelab/{kernel}: set COMPILED_FROM = \"{expected}\" (a file it is compiled from "
        "has changed, and numba would otherwise load code compiled from the old one)")


def test_every_kernel_file_is_named_and_every_file_it_reads_is_in_the_key():
    for kernel, sources in _compiled._COMPILED_FROM.items():
        assert kernel in _compiled._SOURCES
        assert set(sources) <= set(_compiled._SOURCES)
