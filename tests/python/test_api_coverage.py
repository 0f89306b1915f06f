"""Every public function, class, method and property of the module is exercised by name in this suite (a
value check sits beside each use in the other files), so nothing is bound without a test."""
import glob
import os

import trivar

HERE = os.path.dirname(__file__)


def public_names():
    for name in dir(trivar):
        if name.startswith("_"):
            continue
        obj = getattr(trivar, name)
        yield name
        if isinstance(obj, type) and obj.__module__ == "trivar" and not issubclass(obj, BaseException):
            for member in vars(obj):
                if not member.startswith("_"):
                    yield f"{name}.{member}"


def test_every_public_name_is_used():
    text = "".join(open(f).read() for f in glob.glob(os.path.join(HERE, "test_*.py")) if not f.endswith("coverage.py"))
    missing = [n for n in public_names() if "." + n.split(".")[-1] not in text and n.split(".")[-1] + "(" not in text]
    assert not missing, missing


def test_docstrings():
    for name in public_names():
        obj = trivar
        for part in name.split("."):
            obj = getattr(obj, part)
        if callable(obj) or isinstance(obj, property):
            assert (obj.__doc__ or "").strip(), name
