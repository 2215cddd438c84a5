"""Records of arrays that numba kernels pass by reference (one pointer per call).

A kernel's data (the contact stepper's model and work arrays: dozens of arrays) travelled
as named tuples, which numba passes by value: every array is expanded into its pointer,
shape and strides at every call, in the typing, the lowering and the machine code of every
kernel that passes the tuple on. A :class:`JitStruct` is a numba ``StructRef``: the kernels
read its fields with the same syntax (``ws.lam``) and it is passed as one pointer (the
stepper compiles in 78 s instead of 101 s, its LLVM work 33 s instead of 53 s;
docs/performance.md, "Compile time and the test suite").

Theory: none (how kernel data are passed; results are bit-identical either way).

Declare the fields as annotations of a subclass decorated with :func:`jit_struct`::

    @jit_struct
    class Work(JitStruct):
        lam: np.ndarray
        n: int

Build it in a kernel with ``Work(lam, n)`` (positional, in the order declared); Python code
reads its fields as attributes (each read boxes every field: for tests and tools, not for
loops).
"""

from __future__ import annotations

import copy
import sys

from numba import njit
from numba.core import types
from numba.core.extending import intrinsic, overload
from numba.experimental import structref


class JitStruct(structref.StructRefProxy):
    """Python side of a record made by :func:`jit_struct`: its fields read as attributes."""

    __slots__ = ()
    FIELDS: tuple[str, ...] = ()

    def __getattr__(self, name: str):
        fields = type(self).FIELDS
        if name not in fields:
            raise AttributeError(f"{type(self).__name__!r} has no field {name!r}")
        return _field_values(self)[fields.index(name)]

    def __deepcopy__(self, memo) -> JitStruct:
        """A copy of every field (built from Python: numba compiles the constructor once
        per process; for tools, not for loops)."""
        return type(self)(*(copy.deepcopy(v, memo) for v in _field_values(self)))

    def __repr__(self) -> str:
        return f"{type(self).__name__}({', '.join(type(self).FIELDS)})"


def jit_struct(cls: type[JitStruct]) -> type[JitStruct]:
    """Make ``cls`` (a :class:`JitStruct` subclass whose annotations are its fields) a
    numba record passed by reference. Its numba type class is ``<cls>Type``, put in the
    same module (the cache pickles it by name)."""
    fields = tuple(n for n in cls.__dict__.get("__annotations__", {}) if n != "FIELDS")
    name = f"{cls.__name__}Type"
    typ = type(name, (types.StructRef,), {
        "__module__": cls.__module__, "__qualname__": name,
        "preprocess_fields": _unliteral_fields})
    setattr(sys.modules[cls.__module__], name, typ)
    structref.register(typ)
    cls.FIELDS = fields
    structref.define_boxing(typ, cls)
    _define_constructor(cls, typ, fields)
    return cls


def _define_constructor(cls, typ, fields) -> None:
    """``cls(*fields)`` in a kernel (numba's own constructor names its record ``st``,
    which a field of that name shadows)."""
    params = ", ".join(fields)
    sets = "\n".join(f"        _rec_.{f} = {f}" for f in fields)
    source = (f"def ctor({params}):\n"
              f"    rec_type = typ(list(zip({list(fields)!r}, [{params}])))\n"
              f"    def impl({params}):\n"
              f"        _rec_ = new(rec_type)\n{sets}\n"
              f"        return _rec_\n"
              f"    return impl\n")
    scope = {"typ": typ, "new": structref.new}
    exec(source, scope)
    overload(cls)(scope["ctor"])


def _unliteral_fields(self, fields):
    return tuple((name, types.unliteral(t)) for name, t in fields)


@intrinsic
def _as_tuple(typingctx, s):
    """Every field of the record ``s``, in order, as a tuple."""
    field_types = list(s.field_dict.values())
    tup = types.Tuple(field_types)

    def codegen(context, builder, sig, args):
        data = structref._Utils(context, builder, s).get_data_struct(args[0])
        values = [getattr(data, name) for name in s.field_dict]
        for t, v in zip(field_types, values, strict=True):
            context.nrt.incref(builder, t, v)
        return context.make_tuple(builder, tup, values)

    return tup(s), codegen


@njit(cache=True)
def _field_values(s):
    return _as_tuple(s)
