"""Docstrings and annotations for the compiled modules (README "Compiled hot path").

mypyc keeps neither: a compiled function is a builtin whose ``__doc__`` is None (read-only)
and whose signature has no annotations; a compiled class has ``__doc__ == ''``. So
``help(axisline.motion.profiles.plan)`` and ``inspect.signature`` would show less than the
plain-Python install. A compiled module ends with ``document(globals())``; in the compiled
install this reads the module's own source (the ``.py`` beside the extension: the editable
install and the wheel both ship it) with ``ast`` and

- replaces each public function by a thin Python function with the source's name,
  parameters, defaults, annotations and docstring, which calls the compiled one;
- gives each public class its docstring and its ``__init__``'s signature (``__signature__``,
  annotations as in the source), and replaces each public method (plain, ``classmethod``,
  ``staticmethod``) by such a wrapper, except the methods the module names as hot.

Only interpreted callers pass through a wrapper (one Python frame: measured +13 ns on a
146 ns ``Profile.sample`` call; nothing measurable on ``plan``, ~8 us): compiled code calls
the compiled function or method directly (mypyc binds those calls at compile time, not
through the module or class dict), so the hot path does not change. Methods that run every
cycle through interpreted code (called by a device, or handed to the scheduler as bound
methods: ``Profile.sample``, ``Axis.position_loop``, ``AxisUnit.loop``, ...) are left
compiled-only via ``hot=``; tests/test_compiled.py runs example lines and fails if any
wrapper runs per cycle. Properties and dunder methods are left too (C slots: a Python
replacement would slow every attribute access or construction). Their docstrings stay in
the source only.

Reading the sources costs ~20 ms at import (``ast.parse`` of the four modules).

In plain Python (AXISLINE_COMPILE=0, or a module imported from its .py) ``document`` does
nothing: the objects are the source's own. Annotations are kept as the source's strings
(every compiled module has ``from __future__ import annotations``), as plain Python does.
"""

from __future__ import annotations

import ast
import dataclasses
import inspect
from pathlib import Path
from typing import Any, Callable

__all__ = ["document"]

_EMPTY = inspect.Parameter.empty
_MYPYC_FILLER = "mypyc filler docstring"  # mypyc's __doc__ for a class it builds as a Python class


def document(namespace: dict[str, Any], hot: dict[str, tuple[str, ...]] | None = None) -> None:
    """Attach the source's docstrings and annotations to a compiled module's public names.

    `namespace` is the module's ``globals()``; `hot` maps a class name to the methods that
    stay compiled-only (called every cycle from interpreted code).
    """
    origin = str(namespace.get("__file__") or "")
    if not origin or origin.endswith(".py"):
        return  # plain Python: nothing was compiled away
    name = str(namespace["__name__"])
    source = Path(origin).with_name(name.rsplit(".", 1)[-1] + ".py")
    if not source.is_file():
        return  # an install without sources: the compiled objects as they are
    tree = ast.parse(source.read_text(encoding="utf-8"), str(source))
    public = namespace.get("__all__")
    hot = hot or {}
    for node in tree.body:
        if public is not None and node.__class__ in (ast.FunctionDef, ast.ClassDef) and node.name not in public:
            continue
        if isinstance(node, ast.FunctionDef) and not node.name.startswith("_"):
            compiled = namespace.get(node.name)
            if _is_compiled(compiled):
                namespace[node.name] = _wrapper(node, compiled, namespace, node.name)
        elif isinstance(node, ast.ClassDef) and not node.name.startswith("_"):
            cls = namespace.get(node.name)
            if isinstance(cls, type):
                _document_class(node, cls, namespace, set(hot.get(node.name, ())))


def _is_compiled(obj: object) -> bool:
    return inspect.isbuiltin(obj) or inspect.ismethoddescriptor(obj)


def _document_class(node: ast.ClassDef, cls: type, namespace: dict[str, Any], hot: set[str]) -> None:
    signature = _class_signature(node, cls, namespace)
    if signature is not None:
        cls.__signature__ = signature  # type: ignore[attr-defined]
    doc = ast.get_docstring(node, clean=False)
    if doc is None and dataclasses.is_dataclass(cls):
        # what @dataclass writes when the class has none, from the source's annotations
        doc = cls.__name__ + str(inspect.signature(cls)).replace(" -> None", "")
    if cls.__doc__ != doc and (doc is not None or cls.__doc__ in ("", _MYPYC_FILLER)):
        cls.__doc__ = doc
    for item in node.body:
        if not isinstance(item, ast.FunctionDef) or item.name.startswith("_") or item.name in hot:
            continue
        kinds = {_decorator_name(d) for d in item.decorator_list}
        raw = cls.__dict__.get(item.name)
        qualname = f"{cls.__qualname__}.{item.name}"
        if not kinds and _is_compiled(raw):
            setattr(cls, item.name, _wrapper(item, raw, namespace, qualname))
        elif kinds == {"classmethod"} and _is_compiled(raw):
            # a classmethod_descriptor is called with the class first, like the function
            setattr(cls, item.name, classmethod(_wrapper(item, raw, namespace, qualname)))
        elif kinds == {"staticmethod"} and isinstance(raw, staticmethod) and _is_compiled(raw.__func__):
            setattr(cls, item.name, staticmethod(_wrapper(item, raw.__func__, namespace, qualname)))


def _decorator_name(node: ast.expr) -> str:
    return node.id if isinstance(node, ast.Name) else ast.unparse(node)


def _class_signature(node: ast.ClassDef, cls: type, namespace: dict[str, Any]) -> inspect.Signature | None:
    """What ``inspect.signature(cls)`` gives in plain Python, for a compiled class."""
    init = cls.__dict__.get("__init__")
    if inspect.isfunction(init):
        # a dataclass: its __init__ was generated at import, with the right parameters, but
        # mypyc hands it evaluated (and partly wrong) annotations; the source's fields say
        fields = {
            item.target.id: ast.unparse(item.annotation)
            for item in node.body
            if isinstance(item, ast.AnnAssign) and isinstance(item.target, ast.Name)
        }
        sig = inspect.signature(init)
        params = [p.replace(annotation=fields.get(p.name, p.annotation)) for p in sig.parameters.values()]
        return sig.replace(parameters=params[1:])
    for item in node.body:
        if isinstance(item, ast.FunctionDef) and item.name == "__init__":
            sig = _signature(item, namespace)
            return sig.replace(parameters=list(sig.parameters.values())[1:])
    return None


def _signature(node: ast.FunctionDef, namespace: dict[str, Any]) -> inspect.Signature:
    """The signature plain Python gives the function `node`: defaults evaluated in the module."""
    a = node.args
    P = inspect.Parameter
    params: list[inspect.Parameter] = []
    positional = [*a.posonlyargs, *a.args]
    defaults: list[ast.expr | None] = [None] * (len(positional) - len(a.defaults)) + list(a.defaults)
    for index, (arg, default) in enumerate(zip(positional, defaults)):
        kind = P.POSITIONAL_ONLY if index < len(a.posonlyargs) else P.POSITIONAL_OR_KEYWORD
        params.append(P(arg.arg, kind, default=_value(default, namespace), annotation=_annotation(arg.annotation)))
    if a.vararg is not None:
        params.append(P(a.vararg.arg, P.VAR_POSITIONAL, annotation=_annotation(a.vararg.annotation)))
    for arg, kw_default in zip(a.kwonlyargs, a.kw_defaults):
        params.append(P(arg.arg, P.KEYWORD_ONLY, default=_value(kw_default, namespace),
                        annotation=_annotation(arg.annotation)))
    if a.kwarg is not None:
        params.append(P(a.kwarg.arg, P.VAR_KEYWORD, annotation=_annotation(a.kwarg.annotation)))
    return inspect.Signature(params, return_annotation=_annotation(node.returns))


def _annotation(node: ast.expr | None) -> Any:
    # `from __future__ import annotations`: plain Python keeps the source text
    return _EMPTY if node is None else ast.unparse(node)


def _value(node: ast.expr | None, namespace: dict[str, Any]) -> Any:
    if node is None:
        return _EMPTY
    # evaluated once, in the module, as `def` does (at the end of the import, so every
    # constant a default names exists)
    return eval(compile(ast.Expression(node), "<default>", "eval"), namespace)  # noqa: S307


def _plain(sig: inspect.Signature) -> tuple[str, str]:
    """The wrapper's parameter list (defaults by reference) and the call passing them on."""
    params: list[str] = []
    call: list[str] = []
    P = inspect.Parameter
    kinds = [p.kind for p in sig.parameters.values()]
    for p in sig.parameters.values():
        if p.kind is P.KEYWORD_ONLY and P.VAR_POSITIONAL not in kinds and "*" not in params:
            params.append("*")
        if p.kind is P.VAR_POSITIONAL:
            params.append(f"*{p.name}")
            call.append(f"*{p.name}")
        elif p.kind is P.VAR_KEYWORD:
            params.append(f"**{p.name}")
            call.append(f"**{p.name}")
        else:
            params.append(p.name if p.default is _EMPTY else f"{p.name}=__defaults[{p.name!r}]")
            call.append(f"{p.name}={p.name}" if p.kind is P.KEYWORD_ONLY else p.name)
        if p.kind is P.POSITIONAL_ONLY and kinds.count(P.POSITIONAL_ONLY) == len(call):
            params.append("/")
    return ", ".join(params), ", ".join(call)


def _wrapper(node: ast.FunctionDef, compiled: Callable[..., Any], namespace: dict[str, Any],
             qualname: str) -> Callable[..., Any]:
    """A Python function with `node`'s signature and docstring that calls `compiled`."""
    sig = _signature(node, namespace)
    params, call = _plain(sig)
    # A closure built in the module's namespace: `__globals__` is the module's, as for the
    # source's own function (typing.get_type_hints resolves the annotations there), and the
    # module dict gets no new name.
    text = (f"def __make(__compiled, __defaults):\n"
            f"    def {node.name}({params}):\n"
            f"        return __compiled({call})\n"
            f"    return {node.name}\n")
    scope: dict[str, Any] = {}
    exec(compile(text, f"<axisline._docs wrapper of {namespace['__name__']}.{qualname}>", "exec"),  # noqa: S102
         namespace, scope)
    defaults = {p.name: p.default for p in sig.parameters.values() if p.default is not _EMPTY}
    function = scope["__make"](compiled, defaults)
    function.__qualname__ = qualname
    function.__module__ = namespace["__name__"]
    function.__doc__ = ast.get_docstring(node, clean=False)
    function.__annotations__ = {
        p.name: p.annotation for p in sig.parameters.values() if p.annotation is not _EMPTY
    }
    if sig.return_annotation is not _EMPTY:
        function.__annotations__["return"] = sig.return_annotation
    return function
