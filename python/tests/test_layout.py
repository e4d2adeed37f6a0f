"""The ctypes mirrors (fracterra/_structs.py) against the C headers: a small C program compiled here
prints every struct's size, every field's offset and every options default, which must equal what
ctypes computes from the Python side."""
import ctypes
import os
import shutil
import subprocess

import pytest

from fracterra import _lib, _structs as S

_ROOT = os.path.join(os.path.dirname(__file__), os.pardir, os.pardir)
INCLUDE = os.environ.get("FRACTERRA_INCLUDE", os.pathsep.join(
    [os.path.join(_ROOT, "include"), os.path.join(_ROOT, "build", "include")])).split(os.pathsep)
CC = os.environ.get("CC", "cc")


def _is_struct(t):
    return isinstance(t, type) and issubclass(t, ctypes.Structure)


def _is_pointer(t):
    return t in (ctypes.c_char_p, ctypes.c_void_p) or (isinstance(t, type) and (
        issubclass(t, ctypes._Pointer) or issubclass(t, ctypes._CFuncPtr)))


def _leaves(cls, obj, cpath, ppath):
    """(C access path, Python value) of every scalar or pointer field, nested structs flattened."""
    names = getattr(cls, "_c_field_names_", {})
    for f, t in cls._fields_:
        cf = names.get(f, f)
        val = getattr(obj, f)
        if _is_struct(t):
            yield from _leaves(t, val, cpath + cf + ".", ppath + f + ".")
        elif _is_pointer(t):
            yield cpath + cf, "ptr", int(bool(val))
        elif issubclass(t, ctypes.Array):
            continue
        else:
            yield cpath + cf, "num", float(val)


def _program():
    lines = ["#include <stdio.h>", "#include <stddef.h>", "#include <fracterra/fracterra.h>",
             "int main(void) {"]
    expect = {}
    for cls in S.ALL:
        n = cls._c_name_
        names = getattr(cls, "_c_field_names_", {})
        lines.append('printf("size %s %%zu\\n", sizeof(%s));' % (n, n))
        expect["size " + n] = str(ctypes.sizeof(cls))
        for f, _t in cls._fields_:
            cf = names.get(f, f)
            lines.append('printf("off %s.%s %%zu\\n", offsetof(%s, %s));' % (n, cf, n, cf))
            expect["off %s.%s" % (n, cf)] = str(getattr(cls, f).offset)
        macro = getattr(cls, "_c_default_", None)
        if macro:
            var = "d_" + n
            lines.append("{ %s %s = %s;" % (n, var, macro))
            for cpath, kind, val in _leaves(cls, cls.default(), "", ""):
                key = "def %s.%s" % (n, cpath)
                if kind == "ptr":
                    lines.append('printf("%s %%d\\n", %s.%s != NULL);' % (key, var, cpath))
                    expect[key] = str(val)
                else:
                    lines.append('printf("%s %%.17g\\n", (double)%s.%s);' % (key, var, cpath))
                    expect[key] = "%.17g" % val
            lines.append("}")
    for name in ("FT_OK", "FT_E_INVALID", "FT_E_NOMEM", "FT_E_IO", "FT_E_FORMAT", "FT_E_EMPTY",
                 "FT_E_CANCELLED", "FT_E_NUMERIC", "FT_E_UNSUPPORTED"):
        lines.append('printf("enum %s %%d\\n", %s);' % (name, name))
        expect["enum " + name] = str(getattr(_lib, name))
    lines += ["return 0;", "}"]
    return "\n".join(lines) + "\n", expect


@pytest.mark.skipif(shutil.which(CC) is None, reason="no C compiler")
def test_struct_layouts_and_defaults_match_the_headers(tmp_path):
    src, expect = _program()
    (tmp_path / "layout.c").write_text(src)
    exe = tmp_path / "layout"
    subprocess.run([CC, "-std=c11"] + ["-I" + d for d in INCLUDE] + [str(tmp_path / "layout.c"), "-o", str(exe)],
                   check=True)
    out = subprocess.run([str(exe)], check=True, capture_output=True, text=True).stdout
    got = dict(line.rsplit(" ", 1) for line in out.splitlines())
    assert got.keys() == expect.keys()
    bad = {k: (expect[k], got[k]) for k in expect if expect[k] != got[k]}
    assert bad == {}, "Python mirror (left) differs from the C header (right): %r" % bad
    assert len(S.ALL) >= 30
